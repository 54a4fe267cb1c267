// The tracked fronts of the finite-volume solver (`--fronts tracked`, with `--time-stepping
// heun`): the wet fraction of the cells a dry-bed front is moving into, and the invariant
// correction after each step. Why and how: front_kernels.hpp and docs/hydro.md, "Wet/dry fronts".
// The solver calls it at these points of a step: fix() and find_tips() before each stage
// (the fused sweep then gives each tip's faces the wedge's state and shuts its dry face),
// grow() and fix_row()/fix_done() as the stage writes its state, correct_invariants()
// after the step.
//
// Arrays are the solver's padded layout (two ghost layers, row-major, x fastest).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
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

// What fix() learns about each cell of the state it fixes, for the passes after it on the
// same state (one byte per cell): it reads the same neighbours, so those passes need not.
enum FrontMark : unsigned char {
    kMayBeTip = 1,       // may_be_tip(): find_tips looks closer
    kThinEastFace = 2,   // the face to the east neighbour may take an invariant exchange
    kThinSouthFace = 4,  // the face to the south neighbour may
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

    // alpha_out = alpha_in made consistent with h on the rows' columns, a copy elsewhere
    // (alpha_out may be alpha_in): 1 in wet cells with no dry neighbour, 0 in dry cells
    // with no wet one; a wet cell's alpha at least its depth over its deepest neighbour's.
    // With `grown`, alpha_in as grow() left it (its cells grown by the tips; then
    // alpha_out must not be alpha_in). It marks the cells and faces (FrontMark) that
    // find_tips and correct_invariants then look at on this state (h and alpha_out as
    // they are now).
    void fix(const std::vector<double>& h, const std::vector<double>& z, const std::vector<ColumnRange>& cols,
             const std::vector<double>& alpha_in, std::vector<double>& alpha_out, bool grown = false);
    // fix() in parts, for a caller that fixes each row as soon as h is final in it and in
    // its neighbours (while they are in cache): fix_row for every interior row j (rows in
    // any order, on any thread), then fix_done once.
    void fix_row(const std::vector<double>& h, const std::vector<double>& z, const std::vector<ColumnRange>& cols,
                 const std::vector<double>& alpha_in, std::vector<double>& alpha_out, bool grown, int j);
    void fix_done(const std::vector<double>& h, const std::vector<ColumnRange>& cols, const std::vector<double>& alpha_in,
                  std::vector<double>& alpha_out, bool grown);

    // The tip cells of state (h, hu, hv, alpha) within the rows' column ranges (interior
    // rows), each with its back face's wedge state; per row, in column order. Uses the
    // last fix()'s marks where they hold (its state and columns, cells not beside a ghost).
    void find_tips(const std::vector<double>& h, const std::vector<double>& hu, const std::vector<double>& hv,
                   const std::vector<double>& alpha, const std::vector<double>& z, const std::vector<double>& g_n2,
                   const std::vector<ColumnRange>& cols);
    const std::vector<Tip>& tips(int j) const { return tips_[std::size_t(j)]; }
    bool any_tips() const { return any_; }

    // alpha_in grown by dt times the tips' rates, what overflows a full cell starting the
    // next one: kept as the cells it changes, for fix() with `grown` (no copy of the array).
    void grow(const std::vector<double>& alpha_in, double dt);

    // The invariant correction on every interior face of the last fix()'s columns, x
    // faces then y faces, on the state that fix() saw (h with the discharges hu, hv).
    // Returns the largest CFL rate (a_x/dx + a_y/dy) of the cells it changed (0 if none).
    double correct_invariants(const std::vector<double>& h, std::vector<double>& hu, std::vector<double>& hv,
                              const std::vector<double>& z, const std::vector<double>& g_n2);

private:
    std::size_t at(int i, int j) const { return std::size_t(j + 2) * stride_ + std::size_t(i + 2); }
    int nx_, ny_;
    std::size_t stride_;
    double dx_, dy_, g_, dry_;
    std::vector<std::vector<Tip>> tips_;  // per interior row
    bool any_ = false;
    // The last fix(): per cell its FrontMark bits (padded layout; valid within marked_cols_),
    // per row their union, and the arrays it fixed (find_tips uses the marks on those only).
    std::vector<unsigned char> marks_, row_marks_;
    std::vector<ColumnRange> marked_cols_;
    // grow()'s result: per padded row (j + 2), the interior columns changed and their
    // wet fraction; and a scratch slot per cell (-1 between calls).
    std::vector<std::vector<std::pair<int, double>>> growth_;
    std::vector<int> slot_;
    const double* marked_h_ = nullptr;
    const double* marked_alpha_ = nullptr;
    // Per y face row (the face below row j): the columns whose face moves discharge
    // north and how much [m^2/s], nonzero only, in column order.
    std::vector<std::vector<std::pair<int, double>>> y_exchange_;
    std::vector<std::vector<std::size_t>> changed_;  // per row: the cells the correction changed
};

}  // namespace flotsam::hydro
