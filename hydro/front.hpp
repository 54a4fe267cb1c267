// The front treatment of the finite-volume solver (issue 14): the wet fraction of the
// cells a dry-bed front is moving into, and the invariant correction after each step.
// Why and how: front_kernels.hpp and docs/hydro.md, "Wet/dry fronts". The solver calls
// it at three points of a step: find_tips() before each stage (the fused sweep then
// gives each tip's faces the wedge's state and shuts its dry face), advance() after each
// stage, correct_invariants() after the step.
//
// Arrays are the solver's padded layout (two ghost layers, row-major, x fastest).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "hydro/column_range.hpp"
#include "hydro/front_kernels.hpp"

namespace flotsam::hydro {

// Direction in which a front moves through a tip cell.
enum class TipDir : std::uint8_t { east, west, north, south };

struct Tip {
    int i = 0;  // interior column of the tip cell
    TipDir dir = TipDir::east;
    TipFace face;  // the back face's state (velocity toward the tip) and the growth rate
};

class FrontTracker {
public:
    // nx, ny interior cells; stride = nx + 4; dx, dy [m].
    FrontTracker(int nx, int ny, double dx, double dy, double g, double dry_depth);

    // The wet fraction at the start: 1 where h > dry_depth, else 0 (padded, ghosts too).
    void reset(const std::vector<double>& h, std::vector<double>& alpha) const;
    // Ghost cells' wet fraction: mirrored at the sides marked (walls; west, east, south,
    // north), elsewhere from their depth (full where wet).
    void fill_ghosts(const std::vector<double>& h, std::vector<double>& alpha, const std::array<bool, 4>& mirror) const;

    // The tip cells of state (h, hu, hv, alpha) within the rows' column ranges (interior
    // rows), each with its back face's wedge state; per row, in column order.
    void find_tips(const std::vector<double>& h, const std::vector<double>& hu, const std::vector<double>& hv,
                   const std::vector<double>& alpha, const std::vector<double>& z, const std::vector<double>& g_n2,
                   const std::vector<ColumnRange>& cols);
    const std::vector<Tip>& tips(int j) const { return tips_[std::size_t(j)]; }
    bool any_tips() const { return any_; }

    // alpha_out = alpha_in grown by dt times the tips' rates; what overflows a full cell
    // starts the next one. (The caller then makes it consistent with a depth: fix().)
    void grow(const std::vector<double>& alpha_in, double dt, std::vector<double>& alpha_out) const;
    // Consistency of alpha with h on the rows' columns: 1 in wet cells with no dry
    // neighbour, 0 in dry cells with no wet one; a wet cell's alpha at least its depth
    // over its deepest neighbour's (its wet part no deeper than the water beside it).
    void fix(const std::vector<double>& h, const std::vector<ColumnRange>& cols, std::vector<double>& alpha) const;

    // The invariant correction on every interior face, x faces then y faces, over the
    // rows' columns. Returns the largest CFL rate (a_x/dx + a_y/dy) of the cells it
    // changed (0 if none).
    double correct_invariants(const std::vector<double>& h, std::vector<double>& hu, std::vector<double>& hv,
                              const std::vector<double>& z, const std::vector<double>& g_n2, const std::vector<ColumnRange>& cols);

private:
    std::size_t at(int i, int j) const { return std::size_t(j + 2) * stride_ + std::size_t(i + 2); }
    int nx_, ny_;
    std::size_t stride_;
    double dx_, dy_, g_, dry_;
    std::vector<std::vector<Tip>> tips_;  // per interior row
    bool any_ = false;
    std::vector<double> y_exchange_;                 // per y face (below row j, padded layout): discharge moved north [m^2/s]
    std::vector<unsigned char> y_any_;               // per face row: y_exchange_ was written this step (else it is not read)
    std::vector<std::vector<std::size_t>> changed_;  // per row: the cells the correction changed
};

}  // namespace flotsam::hydro
