// The split step (`--time-stepping split`, the default; kernels in split_rows.hpp).
//
// An x sweep and a y sweep, their order alternating from step to step; each sweep is
// one pass over the rows (the x sweep row by row, the y sweep with ring buffers of rows
// as the Heun stage has, heun_stage.cpp), from now_ through mid_ into next_, which then
// becomes the state (next_ keeps U^n for a step redone for positivity). The second
// sweep applies the friction of the whole step. Ghosts are filled before each sweep at
// the half step.
#include <omp.h>

#include <algorithm>

#include "hydro/padded_rows.hpp"
#include "hydro/solver.hpp"
#include "hydro/split_rows.hpp"

namespace flotsam::hydro {

namespace {
using namespace split;
using padded::clip;
using padded::widen;
}  // namespace

template <class Real>
void BasicSolver<Real>::split_step(double dt) {
    const bool x_first = sweep_order_[0] == 0.0;
    const double t_half = time_ + 0.5 * dt;
    sweep(x_first ? Axis::x : Axis::y, false, dt, t_half, now_, state_changed_outside_, mid_);
    sweep(x_first ? Axis::y : Axis::x, true, dt, t_half, mid_, false, next_);
    now_.swap(next_);
    if (state_changed_outside_) std::fill(next_.bound.begin(), next_.bound.end(), ColumnRange{0, grid_.nx});
    sweep_order_[0] = x_first ? 1.0 : 0.0;
}

template <class Real>
void BasicSolver<Real>::sweep(Axis axis, bool last, double dt, double t, State& in, bool whole_rows, State& out) {
    fill_ghosts(in.h, in.hu, in.hv, t);
    const bool x_sweep = axis == Axis::x;
    // The pump's source goes with the x sweep (a depth [m] added after its update).
    const SweepPlan plan{&in, &out, last, dt, x_sweep ? dt * forcing_.pump_rate(t) : 0.0};
    find_active_columns(in.bound, whole_rows, in.h, in.hu, in.hv, plan.pump_depth != 0.0);
    balance_strips();
    long fixes = 0;
    Real worst = 0, amax = 0;
#pragma omp parallel reduction(+ : fixes) reduction(min : worst) reduction(max : amax)
    {
        padded::flush_subnormals();
        const int tid = omp_get_thread_num();
        const auto [j0, j1] = strip_rows(tid, omp_get_num_threads());
        Array& mem = work_[std::size_t(tid)];
        if (mem.size() < Buffers<Real>::kRows * stride_) mem.assign(Buffers<Real>::kRows * stride_, Real(0));
        if (x_sweep)
            x_sweep_strip(plan, mem, j0, j1, fixes, worst, amax);
        else
            y_sweep_strip(plan, mem, j0, j1, fixes, worst, amax);
    }
    if (x_sweep) add_transfer(dt);
    stats_.negative_depth_fixes += fixes;
    stats_.min_depth_seen = std::min(stats_.min_depth_seen, double(worst));
    out.bound = active_;
    if (last) {
        // The pump cells' rate after the source (the update's rate saw them before it).
        double rate = amax;
        for (std::size_t p : pump_cells_)
            if (plan.pump_depth != 0.0) rate = std::max(rate, cell_rate(out.h[p], out.hu[p], out.hv[p]));
        max_wave_rate_ = rate;
    }
}

template <class Real>
void BasicSolver<Real>::x_sweep_strip(const SweepPlan& p, Array& mem, int j0, int j1, long& fixes, Real& worst, Real& amax) {
    const Buffers<Real> w(mem.data(), stride_);
    const Sweep<Real> s = sweep_constants();
    const Real dt = Real(p.dt), friction_dt = p.last ? dt : Real(0), pump_depth = Real(p.pump_depth);
    State &in = *p.in, &out = *p.out;
    for (int j = j0; j < j1; ++j) {
        auto row = [&](Array& a) { return padded::row(a, j, stride_); };
        const ColumnRange cols = active_[std::size_t(j)];
        // The output is exactly zero outside the columns computed now.
        for (Array* a : {&out.h, &out.hu, &out.hv}) padded::clear_outside(row(*a), out.bound[std::size_t(j)], cols);
        face_mass_[0][std::size_t(j)] = face_mass_[1][std::size_t(j)] = 0.0;
        if (cols.empty()) continue;
        auto run = [&]<bool kFriction, bool kRate>() {
            return x_row<Real, kFriction, kRate>(s, cols, dt, friction_dt, row(in.h), row(in.hu), row(in.hv), row(z_),
                                                   row(g_n2_), w, row(out.h), row(out.hu), row(out.hv), fixes, worst, amax);
        };
        const auto [west_mass, east_mass] = p.last ? run.template operator()<true, true>() : run.template operator()<false, false>();
        face_mass_[0][std::size_t(j)] = west_mass;
        face_mass_[1][std::size_t(j)] = east_mass;
        for (std::size_t k = pump_row_start_[std::size_t(j)]; p.pump_depth != 0.0 && k < pump_row_start_[std::size_t(j) + 1]; ++k)
            out.h[pump_cells_[k]] += pump_depth;
    }
}

template <class Real>
void BasicSolver<Real>::y_sweep_strip(const SweepPlan& p, Array& mem, int j0, int j1, long& fixes, Real& worst, Real& amax) {
    const Buffers<Real> w(mem.data(), stride_);
    const int nx = grid_.nx, ny = grid_.ny;
    const Sweep<Real> s = sweep_constants();
    const Real dt = Real(p.dt), friction_dt = p.last ? dt : Real(0);
    const Real hdt_y = Real(0.5 * p.dt / grid_.dy);
    State &in = *p.in, &out = *p.out;
    auto row = [&](Array& a, int j) { return padded::row(a, j, stride_); };
    auto active = [&](int j) { return j >= 0 && j < ny ? active_[std::size_t(j)] : ColumnRange{}; };
    // Row j's update needs the primitives of rows j-2 .. j+2, the slopes and predictor of
    // rows j-1 .. j+1 and the faces below rows j and j+1, over its columns; each ring row
    // is computed over the columns its users need.
    auto primitives = [&](int j) {
        ColumnRange c = widen(active(j), 2);
        for (int k = j - 2; k <= j + 2; ++k) c = hull(c, active(k));
        c = clip(c, -kGhost, nx + kGhost);
        y_primitives_row(s, c.begin + kGhost, c.end + kGhost, row(in.h, j), row(in.hu, j), row(in.hv, j), row(z_, j), w, j + kGhost);
    };
    auto slopes = [&](int j) {
        const ColumnRange c = hull(hull(active(j - 1), active(j)), active(j + 1));
        y_slopes_row(s, c.begin + kGhost, c.end + kGhost, hdt_y, row(in.h, j - 1), row(in.h, j), row(in.h, j + 1), w, j + kGhost);
    };
    auto faces = [&](int j) {
        const ColumnRange c = hull(active(j - 1), active(j));
        y_faces_row(s, c.begin + kGhost, c.end + kGhost, row(in.h, j - 1), row(in.h, j), w, j + kGhost);
    };
    if (j0 < j1) {
        for (int j = j0 - 2; j < j0 + 2; ++j) primitives(j);
        for (int j = j0 - 1; j < j0 + 1; ++j) slopes(j);
        faces(j0);
    }
    for (int j = j0; j < j1; ++j) {
        primitives(j + 2);
        slopes(j + 1);
        faces(j + 1);
        const ColumnRange cols = active(j);
        for (Array* a : {&out.h, &out.hu, &out.hv}) padded::clear_outside(row(*a, j), out.bound[std::size_t(j)], cols);
        if (cols.empty()) continue;
        auto update = [&]<bool kLast>() {
            y_update_row<Real, kLast, kLast>(s, cols, dt, friction_dt, row(in.h, j), row(in.hu, j), row(in.hv, j), row(g_n2_, j), w,
                                               j + kGhost, row(out.h, j), row(out.hu, j), row(out.hv, j), fixes, worst, amax);
        };
        if (p.last)
            update.template operator()<true>();
        else
            update.template operator()<false>();
    }
}

// Both precisions; the sweeps are instantiated with it (the members of solver.hpp are
// defined in solver.cpp, split_step.cpp, heun_stage.cpp, solver_sides.cpp and
// active_columns.cpp, each instantiating its own).
template void BasicSolver<double>::split_step(double);
template void BasicSolver<float>::split_step(double);

}  // namespace flotsam::hydro
