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

// A convex polygon of at most 8 vertices (a rectangle clipped by four half-planes).
struct FootprintPoly {
    Vec2 p[8];
    int n = 0;
};

// The patches of the last box asked for, kept row by row for the next ask: a body that
// has not moved (the same pose, bit for bit: resting on the ground, held by friction, or
// waiting against a quay) reuses them instead of clipping its cells again. A row of cells
// is clipped only when asked for (`wanted`), so a caller that can rule out a row (no point
// of it shallower than the draft) never pays for its cells. The patches depend on the box
// and the grid only, so the answer is the same bits either way.
class FootprintCache {
public:
    // Whether the patches within x0 ≤ x ≤ x1, y0 ≤ y ≤ y1 (the footprint's part in one row
    // of cells: every patch centroid of the row lies there) are needed [m]. Null: every row.
    using RowFilter = bool (*)(const void* context, double x0, double x1, double y0, double y1);
    // The patches of the rows wanted, in the order footprint_patches gives them.
    const std::vector<FootprintPatch>& patches(const Box& box, const Grid& grid, RowFilter wanted = nullptr,
                                               const void* context = nullptr);
    std::size_t rows_left_out() const { return rows_left_out_; }  // rows the filter ruled out, all asks [-]

private:
    struct Row {
        int j = 0;
        FootprintPoly part;                     // the footprint cut to the row
        double x0 = 0.0, x1 = 0.0;              // the part's x range [m]
        double inner_x0 = 0.0, inner_x1 = 0.0;  // where whole cells lie inside it [m]
        bool clipped = false;                   // `patches` holds its cells
        std::vector<FootprintPatch> patches;
    };
    void set_box(const Box& box, const Grid& grid);
    void clip_row(Row& row) const;

    std::vector<Row> rows_;  // the first `row_count_` are the box's
    std::size_t row_count_ = 0;
    std::vector<char> taken_;  // the rows in `patches_`
    std::vector<FootprintPatch> patches_;
    Box box_;
    Grid grid_;
    bool valid_ = false;
    std::size_t rows_left_out_ = 0;
};

}  // namespace flotsam::debris
