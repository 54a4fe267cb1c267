// Columns [begin, end) of one grid row, in interior indices (ghosts are -2, -1, nx, nx + 1):
// where the finite-volume solver (solver.hpp) and its front treatment (front.cpp) work.
#pragma once
#include <algorithm>

namespace flotsam::hydro {

inline constexpr int kGhost = 2;  // ghost cells on each side of a row and column

struct ColumnRange {
    int begin = 0, end = 0;
    bool empty() const { return begin >= end; }
};

// The smallest range holding both.
inline ColumnRange hull(ColumnRange a, ColumnRange b) {
    if (a.empty()) return b;
    if (b.empty()) return a;
    return {std::min(a.begin, b.begin), std::max(a.end, b.end)};
}

}  // namespace flotsam::hydro
