// Which columns of each row a stage or sweep computes (the dry-land skip), and how the
// rows are shared among threads.
//
// Dry land: a cell whose depth is zero over its whole stencil (2 cells each way in x
// and y) has zero velocities (u = hu * 0) and depths at its faces, so every flux and
// rate of the cell is +0 or -0, whatever the discharges there. If its own h, hu, hv are
// +0 (all bits zero), its update then gives +0 again: the cell need not be computed.
// Per row, only the columns within 2 cells of a nonzero depth in the 5 rows around it,
// and those with a nonzero state, are (find_active_columns). This is exact, not a
// second dry tolerance: a film of 1e-9 m is computed like any water.
#include <omp.h>

#include <algorithm>

#include "hydro/padded_rows.hpp"
#include "hydro/solver.hpp"

namespace flotsam::hydro {

using padded::clip;
using padded::is_zero;
using padded::widen;

template <class Real>
void BasicSolver<Real>::find_active_columns(Stage which, const Array& h, const Array& hu, const Array& hv, bool pumping) {
    find_active_columns(which == Stage::corrector ? mid_.bound : now_.bound, which == Stage::predictor && state_changed_outside_, h, hu, hv,
                        pumping);
    if (which == Stage::predictor) base_nonzero_ = state_nonzero_;
    // The corrector also averages with the base state, which may be nonzero where U1 is not.
    if (which == Stage::corrector)
        for (int j = 0; j < grid_.ny; ++j) {
            ColumnRange& a = active_[std::size_t(j)];
            const ColumnRange before = a;
            a = hull(a, base_nonzero_[std::size_t(j)]);
            stats_.cell_stages_dry -= double(std::max(0, a.end - a.begin) - std::max(0, before.end - before.begin));
        }
}

template <class Real>
void BasicSolver<Real>::find_active_columns(const std::vector<ColumnRange>& bound, bool whole_rows, const Array& h, const Array& hu,
                                            const Array& hv, bool pumping) {
    const int nx = grid_.nx, ny = grid_.ny;
    // Where the input may be nonzero: `bound`, what the last stage computed (whole rows
    // when the state was changed outside step()); ghost rows and columns always. Serial:
    // each scan stops at the first nonzero cell from either end, so it reads few cells
    // more than the dry ones within the bound; a parallel region would cost more.
    for (int j = -kGhost; j < ny + kGhost; ++j) {
        const std::size_t row = std::size_t(j + kGhost) * stride_ + kGhost;  // column i at row + i
        auto at_column = [&](int i) { return std::size_t(std::ptrdiff_t(row) + i); };
        auto state_nonzero = [&](int i) {
            return !(is_zero(h[at_column(i)]) && is_zero(hu[at_column(i)]) && is_zero(hv[at_column(i)]));
        };
        auto depth_nonzero = [&](int i) { return h[at_column(i)] != Real(0); };
        const bool ghost_row = j < 0 || j >= ny;
        const ColumnRange scan = ghost_row || whole_rows ? ColumnRange{0, nx} : bound[std::size_t(j)];
        int b = scan.begin, e = scan.end;
        if (!ghost_row) {  // the cells of the row itself: any bit of the state
            while (b < e && !state_nonzero(b)) ++b;
            while (e > b && !state_nonzero(e - 1)) --e;
            state_nonzero_[std::size_t(j)] = b < e ? ColumnRange{b, e} : ColumnRange{};
        }
        while (b < e && !depth_nonzero(b)) ++b;  // neighbours: the depth
        while (e > b && !depth_nonzero(e - 1)) --e;
        ColumnRange depth = b < e ? ColumnRange{b, e} : ColumnRange{};
        for (int i : {-2, -1, nx, nx + 1})
            if (depth_nonzero(i)) depth = hull(depth, {i, i + 1});
        depth_nonzero_[std::size_t(j + kGhost)] = depth;
    }
    for (int j = 0; j < ny; ++j) {
        ColumnRange a{0, nx};
        if (fv_.skip_dry_land) {
            a = {};
            for (int k = j - 2; k <= j + 2; ++k) a = hull(a, depth_nonzero_[std::size_t(k + kGhost)]);
            a = hull(clip(widen(a, 2), 0, nx), state_nonzero_[std::size_t(j)]);
        }
        if (pumping)
            for (std::size_t k = pump_row_start_[std::size_t(j)]; k < pump_row_start_[std::size_t(j) + 1]; ++k) {
                const int i = int(pump_cells_[k] % stride_) - kGhost;
                a = hull(a, {i, i + 1});
            }
        active_[std::size_t(j)] = a;
        stats_.cell_stages_dry += double(nx - std::max(0, a.end - a.begin));
    }
    stats_.cell_stages += double(grid_.size());
}

template <class Real>
void BasicSolver<Real>::balance_strips() {
    if (work_.size() < std::size_t(omp_get_max_threads())) work_.resize(std::size_t(omp_get_max_threads()));
    // Columns to compute in the rows below each row, to give each thread an equal share
    // (with dry land skipped, rows cost different amounts; up to 10 % on 2 threads).
    const int ny = grid_.ny;
    cumulative_columns_.assign(std::size_t(ny) + 1, 0.0);
    for (int j = 0; j < ny; ++j) {
        const ColumnRange a = active_[std::size_t(j)];
        cumulative_columns_[std::size_t(j) + 1] = cumulative_columns_[std::size_t(j)] + 1.0 + std::max(0, a.end - a.begin);
    }
}

template <class Real>
std::pair<int, int> BasicSolver<Real>::strip_rows(int thread, int threads) const {
    auto first_row = [&](int k) {
        const double share = cumulative_columns_.back() * k / threads;
        return int(std::lower_bound(cumulative_columns_.begin(), cumulative_columns_.end(), share) - cumulative_columns_.begin());
    };
    return {first_row(thread), thread + 1 == threads ? grid_.ny : first_row(thread + 1)};
}

template void BasicSolver<double>::find_active_columns(Stage, const std::vector<double>&, const std::vector<double>&,
                                                       const std::vector<double>&, bool);
template void BasicSolver<float>::find_active_columns(Stage, const std::vector<float>&, const std::vector<float>&,
                                                      const std::vector<float>&, bool);
template void BasicSolver<double>::find_active_columns(const std::vector<ColumnRange>&, bool, const std::vector<double>&,
                                                       const std::vector<double>&, const std::vector<double>&, bool);
template void BasicSolver<float>::find_active_columns(const std::vector<ColumnRange>&, bool, const std::vector<float>&,
                                                      const std::vector<float>&, const std::vector<float>&, bool);
template void BasicSolver<double>::balance_strips();
template void BasicSolver<float>::balance_strips();
template std::pair<int, int> BasicSolver<double>::strip_rows(int, int) const;
template std::pair<int, int> BasicSolver<float>::strip_rows(int, int) const;

}  // namespace flotsam::hydro
