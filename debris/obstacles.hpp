// Obstacles: grid cells the body cannot enter, treated as axis-aligned squares.
//
// The ground under the body is contact (friction, the axis shift), never an obstacle
// (MODEL.md, "Obstacles"; docs/debris.md). A cell blocks where the scene marks a
// building, outside the grid (the flume walls), and where its ground rises above the
// body's bottom by more than the step height: a step on the body's way that it cannot
// ride onto. The bottom is where the body rests (MODEL.md, "Vertical position"): at
// η − d afloat, on the highest ground under its footprint where that is higher, so no
// cell under the footprint is ever above it. Overlap of the body with a blocked cell is
// found by the separating-axis test (oriented box against an axis-aligned square), which
// also gives the push-out normal and penetration depth.
#pragma once
#include <cstdint>
#include <vector>

#include "common/grid.hpp"
#include "debris/box.hpp"

namespace flotsam::debris {

struct ObstacleContact {
    Vec2 normal;         // unit, from the obstacle into the body (the direction that separates) [-]
    double depth = 0.0;  // penetration along normal [m]
    Vec2 point;          // where the impulse acts [m]
};

class ObstacleMap {
public:
    ObstacleMap() = default;
    // bed: ground elevation z per cell [m]; building: 1 where a building stands (empty: none).
    ObstacleMap(const Grid& grid, std::vector<float> bed, std::vector<std::uint8_t> building);

    const Grid& grid() const { return grid_; }
    // Ground elevation of the cell holding (x, y) [m] (clamped to the grid).
    double ground(double x, double y) const { return double(bed_[grid_.index(grid_.cell_i(x), grid_.cell_j(y))]); }
    bool blocked(int i, int j, double bottom, double step_height) const;

    // Highest ground [m] of the cells under `box`, buildings left out (no body rests on a
    // roof; buildings are walls): the cells it reaches into by more than `min_overlap` [m]
    // along every separating axis. −inf where it covers none.
    double highest_ground(const Box& box, double min_overlap) const;
    // Whether a cell that `box` could reach within a step (its bounding box widened by one
    // cell), buildings left out, has ground above `level` [m].
    bool ground_above(const Box& box, double level) const;

    // Appends every overlap of `box` with a blocked cell deeper than `min_depth`.
    void find_contacts(const Box& box, double bottom, double step_height, std::vector<ObstacleContact>& out,
                       double min_depth = 1e-10) const;

private:
    // Cell index range [i0, i1] x [j0, j1] of the cells that the bounding box of `box`,
    // widened by `pad` cells, touches (not clamped to the grid).
    struct CellRange {
        int i0, i1, j0, j1;
    };
    CellRange cells_touching(const Box& box, int pad) const;

    Grid grid_;
    std::vector<float> bed_;
    // The two questions the scans ask of a cell, one number each so that a row is one
    // vectorised max: its ground where no building stands (−inf under a building), and
    // the top of what blocks there (+inf under a building, else the ground) [m].
    std::vector<float> open_ground_;
    std::vector<float> wall_top_;

    // The largest value of each block of block_cells × block_cells cells of a per-cell
    // field, so that a scan can rule out a whole range of cells at once: a body away from
    // walls and rising ground needs no cell-by-cell look.
    struct BlockMax {
        static constexpr int block_cells = 4;
        int nbx = 0, nby = 0;
        std::vector<float> max;
        BlockMax() = default;
        BlockMax(const Grid& grid, const std::vector<float>& cells);
        // Largest value over the cells [i0, i1] x [j0, j1] (inside the grid) and possibly a
        // few more around them: never below the range's own largest value.
        float bound(int i0, int i1, int j0, int j1) const;
    };
    BlockMax open_ground_blocks_;
    BlockMax wall_top_blocks_;
};

}  // namespace flotsam::debris
