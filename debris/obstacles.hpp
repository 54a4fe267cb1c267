// Obstacles: grid cells the body cannot enter, treated as axis-aligned squares.
//
// The ground under the body is contact (friction, the axis shift), never an obstacle
// (MODEL.md, "Obstacles"; docs/debris.md, "Ground and obstacles"). A cell blocks where
// the scene marks a building, outside the grid (the flume walls), and where ground that
// can block (BlockingGround) rises above the body's bottom by more than the step height:
// a step on the body's way that it cannot ride onto. The bottom is where the body rests
// (MODEL.md, "Vertical position"): at η − d afloat, on the highest ground under its
// footprint where that is higher, so no cell under the footprint is ever above it.
// Overlap of the body with a blocked cell is found by the separating-axis test (oriented
// box against an axis-aligned square), which also gives the push-out normal and
// penetration depth.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "common/enum_names.hpp"
#include "common/grid.hpp"
#include "debris/box.hpp"

namespace flotsam::debris {

// Which ground can block a body (docs/debris.md, "Ground and obstacles"): `land`, the
// ground above still water (z > 0: quays, banks above the waterline, streets), so the
// seabed is contact wherever the body goes and the shoreline keeps it in the water until
// the water over the land is deep enough (the paper's "non-contact condition with the
// shoreline"); `any`, every ground cell, seabed included; `none`, no ground (buildings
// and the flume walls only).
enum class BlockingGround { land, any, none };
inline constexpr EnumNames<BlockingGround, 3> blocking_ground_names{
    "blocking ground",
    {{{BlockingGround::land, "land"}, {BlockingGround::any, "any"}, {BlockingGround::none, "none"}}}};
constexpr const auto& enum_names(BlockingGround) { return blocking_ground_names; }

struct ObstacleCollision {
    Vec2 normal;         // unit, from the obstacle into the body (the direction that separates) [-]
    double depth = 0.0;  // penetration along normal [m]; negative: the gap to a cell near the body
    Vec2 point;          // where the impulse acts: on the body (a corner, or the middle of its part of a face) [m]
    std::int32_t building = 0;  // the building of the blocked cell (ObstacleMap::building_id); 0: ground or the grid's edge
};

// The water over the obstacle grid's cells at the time asked: whether a body floats over a
// land cell or is stopped by it (Blocking below).
class CellWater {
public:
    virtual ~CellWater() = default;
    virtual double depth(int i, int j) const = 0;  // over cell (i, j) [m]
};

// What blocks one body (docs/debris.md, "Ground and obstacles"): a building, the grid's
// edge, and ground that `rule` lets block where it rises above the body's bottom by more
// than the step height; with `water`, such ground blocks only where the water over that
// cell is shallower than the draft (deeper, the body floats over it).
struct Blocking {
    double bottom = 0.0;       // the body's bottom [m]
    double step_height = 0.0;  // [m]
    BlockingGround rule = BlockingGround::any;
    const CellWater* water = nullptr;  // null: ground blocks whatever the water over it
    double draft = 0.0;                // [m]
};

class ObstacleMap {
public:
    ObstacleMap() = default;
    // bed: ground elevation z per cell [m]; building: 1 where a building stands (empty: none).
    // The buildings are numbered as the mask's connected components (building_components)
    // until set_building_ids gives the scene's numbers.
    ObstacleMap(const Grid& grid, std::vector<float> bed, std::vector<std::uint8_t> building);

    // The building of each cell (0: none; size grid().size(), nonzero on the mask's cells).
    void set_building_ids(std::vector<std::int32_t> ids) { building_id_ = std::move(ids); }
    // The building of cell (i, j); 0 off the grid or where none stands.
    std::int32_t building_id(int i, int j) const {
        if (i < 0 || j < 0 || i >= grid_.nx || j >= grid_.ny || building_id_.empty()) return 0;
        return building_id_[grid_.index(i, j)];
    }
    bool has_buildings() const { return !building_id_.empty(); }

    const Grid& grid() const { return grid_; }
    // Ground elevation of the cell holding (x, y) [m] (clamped to the grid).
    double ground(double x, double y) const { return double(bed_[grid_.index(grid_.cell_i(x), grid_.cell_j(y))]); }
    bool blocked(int i, int j, double bottom, double step_height, BlockingGround rule = BlockingGround::any) const;
    bool blocked(int i, int j, const Blocking& by) const;

    // Highest ground [m] of the cells under `box`, buildings left out (no body rests on a
    // roof; buildings are walls): the cells it reaches into by more than `min_overlap` [m]
    // along every separating axis. −inf where it covers none.
    double highest_ground(const Box& box, double min_overlap) const;
    // Whether a cell that `box` could reach within a step (its bounding box widened by one
    // cell), buildings left out, has ground that can block under `rule` above `level` [m].
    bool ground_above(const Box& box, double level, BlockingGround rule = BlockingGround::any) const;

    // Appends every overlap of `box` with a blocked cell deeper than `min_depth` and, with a
    // margin, every blocked cell within `margin` of it (depth down to −margin: the gap). The
    // contacts are the box's own: normal and depth from the separating-axis test of the box
    // itself, the point on it (the margin chooses only which cells are looked at). With a
    // margin, the body's corners across from an overlapped cell's face are gaps as well.
    void find_contacts(const Box& box, const Blocking& by, std::vector<ObstacleCollision>& out, double min_depth = 1e-10,
                       double margin = 0.0) const;
    void find_contacts(const Box& box, double bottom, double step_height, std::vector<ObstacleCollision>& out,
                       double min_depth = 1e-10, BlockingGround rule = BlockingGround::any) const {
        find_contacts(box, Blocking{bottom, step_height, rule}, out, min_depth);
    }

private:
    // Cell index range [i0, i1] x [j0, j1] of the cells that the bounding box of `box`,
    // widened by `pad` cells, touches (not clamped to the grid).
    struct CellRange {
        int i0, i1, j0, j1;
    };
    CellRange cells_touching(const Box& box, int pad) const;
    // Appends the contacts of `box` with blocked cell (i, j) (find_contacts' rules); false
    // where it has none.
    bool cell_contact(const Box& box, int i, int j, const Blocking& by, double min_depth, double margin,
                      std::vector<ObstacleCollision>& out) const;

    Grid grid_;
    std::vector<float> bed_;
    std::vector<std::int32_t> building_id_;  // per cell, 0: none; empty: no building at all
    // The questions the scans ask of a cell, one number each so that a row is one
    // vectorised max: its ground where no building stands (−inf under a building: the
    // resting height), and per BlockingGround rule the top of what blocks there (+inf
    // under a building, the ground where it can block, −inf where nothing does) and the
    // same without the buildings (−inf there: ground_above) [m].
    std::vector<float> open_ground_;
    struct Walls {
        std::vector<float> top;
        std::vector<float> open_top;
    };
    std::array<Walls, 3> walls_;  // indexed by BlockingGround
    const Walls& walls(BlockingGround rule) const { return walls_[std::size_t(rule)]; }

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
    std::array<BlockMax, 3> wall_top_blocks_, open_top_blocks_;  // indexed by BlockingGround
};

}  // namespace flotsam::debris
