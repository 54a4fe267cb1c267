// Moving a field from one uniform cell-centred grid to another covering the same area.
#pragma once
#include <vector>

#include "common/grid.hpp"

namespace flotsam {

// The grid of spacing `spacing` [m] whose first cell starts at the lower-left edge
// (x_min, y_min) [m] and which covers up to (x_max, y_max) [m]; the last row/column may
// overhang by less than one cell.
Grid grid_covering(double x_min, double x_max, double y_min, double y_max, double spacing);

// Resamples `field` on `from` to `to`, axis by axis: where the target cell is larger than
// the source cell, the cell-area average of the overlapping source cells (over the part
// inside the source); otherwise linear interpolation at the target centre (clamped at
// the source's outer centres). Equal grids copy exactly.
std::vector<double> resample(const Grid& from, const std::vector<double>& field, const Grid& to);

}  // namespace flotsam
