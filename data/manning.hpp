// Manning's n as rules over a grid: the roughness zones a scene carries in `manning_n`.
#pragma once
#include <optional>
#include <vector>

#include "common/grid.hpp"

namespace flotsam {

// Manning n inside optional bounds; rules apply in order, the first that holds wins.
struct ManningRule {
    double n = 0.013;                    // [s m^-1/3]
    std::optional<double> x_min, x_max;  // [m], cell centre x in [x_min, x_max)
    std::optional<double> y_min, y_max;  // [m]
};

// n per cell of g (row-major) under `rules`; a cell no rule covers takes the last rule's
// n. Empty rules: an empty field (the run's default applies).
std::vector<double> manning_field(const Grid& g, const std::vector<ManningRule>& rules);

}  // namespace flotsam
