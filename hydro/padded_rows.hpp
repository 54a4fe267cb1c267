// What the solver's loops over rows share (solver*.cpp, heun_stage.cpp, split_step.cpp):
// pointers to a row of a padded field, column-range arithmetic, the zero tests of the
// dry-land skip, and the floating-point mode of a thread.
#pragma once
#include <xmmintrin.h>

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "hydro/column_range.hpp"
#include "hydro/boundary.hpp"

namespace flotsam::hydro::padded {

// Row j (interior index; ghosts -2, -1, ny, ny + 1) of a padded field, at padded column 0.
template <class Real>
Real* row(std::vector<Real>& a, int j, std::size_t stride) {
    return a.data() + std::size_t(j + kGhost) * stride;
}
template <class Real>
const Real* row(const std::vector<Real>& a, int j, std::size_t stride) {
    return a.data() + std::size_t(j + kGhost) * stride;
}

// Flush subnormal numbers to zero on this thread. Friction shrinks discharges in thin
// films geometrically, into the subnormal range, where every operation costs ~100
// cycles; values below 1e-308 carry no physics.
inline void flush_subnormals() { _mm_setcsr(_mm_getcsr() | 0x8040); }

inline bool is_x_side(Side s) { return s == Side::west || s == Side::east; }

inline ColumnRange widen(ColumnRange a, int n) { return a.empty() ? a : ColumnRange{a.begin - n, a.end + n}; }
inline ColumnRange clip(ColumnRange a, int lo, int hi) { return {std::max(a.begin, lo), std::min(a.end, hi)}; }

inline bool is_zero(double x) { return std::bit_cast<std::uint64_t>(x) == 0; }  // +0 only
inline bool is_zero(float x) { return std::bit_cast<std::uint32_t>(x) == 0; }

// Sets the cells of `was` outside `now` to zero (row at padded column 0).
template <class Real>
void clear_outside(Real* row, ColumnRange was, ColumnRange now) {
    if (was.empty()) return;
    if (now.empty()) now = {was.end, was.end};
    for (int i = was.begin; i < std::min(was.end, now.begin); ++i) row[i + kGhost] = Real(0);
    for (int i = std::max(was.begin, now.end); i < was.end; ++i) row[i + kGhost] = Real(0);
}

}  // namespace flotsam::hydro::padded
