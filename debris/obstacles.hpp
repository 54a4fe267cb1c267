// Obstacles: grid cells the body cannot enter, treated as axis-aligned squares.
//
// A cell blocks where its ground is higher than the body's bottom by more than the step
// height, or where the scene marks a building. Cells outside the grid block (the flume
// walls). Overlap of the body with a blocked cell is found by the separating-axis test
// (oriented box against an axis-aligned square), which also gives the push-out normal
// and penetration depth.
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

    // Appends every overlap of `box` with a blocked cell deeper than `min_depth`.
    void find_contacts(const Box& box, double bottom, double step_height, std::vector<ObstacleContact>& out,
                       double min_depth = 1e-10) const;

private:
    Grid grid_;
    std::vector<float> bed_;
    std::vector<std::uint8_t> building_;
};

}  // namespace flotsam::debris
