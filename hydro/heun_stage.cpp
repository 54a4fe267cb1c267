// The two-stage Heun step's stage (`--time-stepping heun`), with the tracked fronts'
// hooks (front.hpp).
//
// A stage sweeps each thread's strip of interior rows once, south to north. The rates
// of row j need the primitive values (eta, u, v) of rows j-2 .. j+2, the limited
// y-slopes of rows j-1 .. j+1 and the y-face fluxes below rows j and j+1. These live in
// small ring buffers of rows (about 46 rows per thread, in the core's cache), each
// computed once, when the sweep first needs it; the rows just outside a strip are
// computed by both threads that need them. Row j's rates are then complete, so it is
// updated at once: the state is read and written once per stage instead of the grid
// being swept six times through full-size scratch arrays. Every expression is the one
// of the unfused scheme (fluxes, then update, per row), so the results are the same
// bits.
#include <omp.h>

#include <algorithm>

#include "hydro/padded_rows.hpp"
#include "hydro/solver.hpp"
#include "hydro/swe_kernels.hpp"
#include "hydro/swe_rows.hpp"

namespace flotsam::hydro {

namespace {
using namespace rows;
using padded::clip;
using padded::widen;

// The ring-buffer rows of one thread's strip: each quantity of a row over the columns
// its users need (interior row j): primitives for the slopes of rows j-1 .. j+1 and the
// x-sweep of row j; y-slopes for the faces below and above row j and its bed slope;
// y-faces for the rows on either side.
template <class Real>
class StageRings {
public:
    StageRings(const Sweep<Real>& s, const std::vector<ColumnRange>& active, const GridState<Real>& in, const std::vector<Real>& z,
               const FrontTracker* front, const RowBuffers<Real>& w, std::size_t stride)
        : s_(s), active_(active), in_(in), z_(z), front_(front), w_(w), stride_(stride) {}

    ColumnRange active(int j) const { return j >= 0 && j < ny() ? active_[std::size_t(j)] : ColumnRange{}; }
    // The tracked fronts' tips of row j, or none.
    const std::vector<Tip>* tips_of(int j) const {
        if (!front_ || !front_->any_tips() || j < 0 || j >= ny()) return nullptr;
        const std::vector<Tip>& row_tips = front_->tips(j);
        return row_tips.empty() ? nullptr : &row_tips;
    }

    void primitives(int j) const {
        ColumnRange c = widen(active(j), 2);
        for (int k = j - 2; k <= j + 2; ++k) c = hull(c, active(k));
        c = clip(c, -kGhost, s_.nx + kGhost);
        primitives_row(s_, c, row(in_.h, j), row(in_.hu, j), row(in_.hv, j), row(z_, j), w_.prim(j + kGhost, 0),
                       w_.prim(j + kGhost, 1), w_.prim(j + kGhost, 2));
    }

    void slopes(int j) const {
        const ColumnRange c = hull(hull(active(j - 1), active(j)), active(j + 1));
        y_slopes_row(s_, c, row(in_.h, j - 1), row(in_.h, j), row(in_.h, j + 1), w_, j + kGhost);
        // First order at y-tips and their y-neighbours; a ghost row as the edge row it
        // mirrors (see x_slopes_at_tips).
        const int as_row = j == -1 ? 0 : (j == ny() ? ny() - 1 : j);
        for (int k = as_row - 1; k <= as_row + 1; ++k)
            if (const std::vector<Tip>* tips = tips_of(k))
                for (const Tip& tip : *tips)
                    if (!is_x(tip.dir) && tip.i >= c.begin && tip.i < c.end)
                        for (int q = 0; q < 4; ++q) w_.slope(j + kGhost, q)[tip.i + kGhost] = Real(0);
    }

    void faces(int j) const {
        y_faces_row(s_, hull(active(j - 1), active(j)), row(in_.h, j - 1), row(in_.h, j), w_, j + kGhost);
        // The y faces of tips: the face below row j is the back face of a north-moving
        // tip in row j and of a south-moving one in row j - 1, the shut face of the others.
        const Real *lo_e = w_.prim(j - 1 + kGhost, 0), *hi_e = w_.prim(j + kGhost, 0);
        const Real *lo_u = w_.prim(j - 1 + kGhost, 1), *hi_u = w_.prim(j + kGhost, 1);
        const Real *lo_h = row(in_.h, j - 1), *hi_h = row(in_.h, j);
        Real *fm = w_.face(j + kGhost, 0), *fl = w_.face(j + kGhost, 1), *fr = w_.face(j + kGhost, 2), *ft = w_.face(j + kGhost, 3);
        for (int k : {j - 1, j})
            if (const std::vector<Tip>* tips = tips_of(k))
                for (const Tip& tip : *tips) {
                    if (is_x(tip.dir)) continue;
                    const int c = tip.i + kGhost;
                    const bool north = tip.dir == TipDir::north;
                    if (north == (k == j)) {
                        store(back_face_flux(s_, tip.face, north ? 1.0 : -1.0, lo_u[c], hi_u[c]), c, fm, fl, fr, ft);
                    } else {
                        FaceFlux f;
                        shut_face_flux(double(lo_e[c]), double(lo_h[c]), double(hi_e[c]), double(hi_h[c]), double(s_.g), f);
                        store(f, c, fm, fl, fr, ft);
                    }
                }
    }

private:
    int ny() const { return int(active_.size()); }
    const Real* row(const std::vector<Real>& a, int j) const { return padded::row(a, j, stride_); }

    const Sweep<Real>& s_;
    const std::vector<ColumnRange>& active_;
    const GridState<Real>& in_;
    const std::vector<Real>& z_;
    const FrontTracker* front_;
    const RowBuffers<Real>& w_;
    std::size_t stride_;
};

}  // namespace

template <class Real>
void BasicSolver<Real>::stage(Stage which, double dt, double t) {
    const StagePlan plan = prepare_stage(which, dt, t);
    long fixes = 0;
    Real worst = 0, amax = 0;
#pragma omp parallel reduction(+ : fixes) reduction(min : worst) reduction(max : amax)
    {
        padded::flush_subnormals();
        const int tid = omp_get_thread_num();
        const auto [j0, j1] = strip_rows(tid, omp_get_num_threads());
        stage_strip(plan, work_[std::size_t(tid)], j0, j1, fixes, worst, amax);
        if (plan.fronts) {
            // The wet fraction of the strip's first and last rows, whose neighbours are
            // final once the threads beside are done and the y ghost rows are filled.
#pragma omp barrier
#pragma omp single
            for (Side side : {Side::south, Side::north})
                fill_side_cells(side, plan.out_forcing[std::size_t(side)], plan.out->h, plan.out->hu, plan.out->hv, plan.t_out, 0,
                                grid_.nx);
            fix_strip_edges(plan, j0, j1);
        }
    }
    stats_.negative_depth_fixes += fixes;
    stats_.min_depth_seen = std::min(stats_.min_depth_seen, double(worst));
    plan.out->bound = active_;
    if (plan.last) max_wave_rate_ = amax;
    if constexpr (kFronts)
        if (plan.fronts) front_->fix_done(plan.out->h, active_, now_.wet_fraction, plan.out->wet_fraction, true);
}

template <class Real>
void BasicSolver<Real>::fix_strip_edges(const StagePlan& plan, int j0, int j1) {
    if constexpr (kFronts) {
        if (j0 < j1) front_->fix_row(plan.out->h, z_, active_, now_.wet_fraction, plan.out->wet_fraction, true, j0);
        if (j0 < j1 - 1) front_->fix_row(plan.out->h, z_, active_, now_.wet_fraction, plan.out->wet_fraction, true, j1 - 1);
    }
}

template <class Real>
typename BasicSolver<Real>::StagePlan BasicSolver<Real>::prepare_stage(Stage which, double dt, double t) {
    StagePlan p;
    p.corrector = which == Stage::corrector;
    // The corrector writes U^{n+1} into next_, not over U^n: step_once swaps the two, and a
    // step redone for positivity (step) finds U^n in next_.h without a copy.
    p.in = p.corrector ? &mid_ : &now_;
    p.out = p.corrector ? &next_ : &mid_;
    p.dt = dt;
    p.last = p.corrector || fv_.order == 1;  // the step's result: remember its CFL rate
    p.fronts = fv_.fronts == FrontTreatment::tracked;
    State& in = *p.in;
    fill_ghosts(in.h, in.hu, in.hv, t);
    p.pump_rate = forcing_.pump_rate(t);  // [m/s] over the source strip
    find_active_columns(which, in.h, in.hu, in.hv, p.pump_rate != 0.0);
    if (p.fronts) prepare_fronts(which, p, dt);
    balance_strips();
    // The output's ghost cells, for its wet fraction's fix in the strip: each row's x
    // ghosts once the row is updated, the y ghost rows after the strips, at the output's
    // time, so that they are those the next stage fills in. Fixed against whatever the
    // buffer held from its last use instead, the edge cells' wet fraction depended on that
    // history, and a run that wrote checkpoints gave other bytes. The forcing is worked
    // out here, before the output exists: a pump that stops within this step takes its
    // level from the step's start (order 2: as the corrector's own fill would; order 1: a
    // step earlier than the next step's fill, which would read this output).
    p.t_out = p.corrector ? t : t + dt;
    if (p.fronts)
        for (Side side : {Side::west, Side::east, Side::south, Side::north})
            p.out_forcing[std::size_t(side)] = side_forcing(side, p.t_out);
    return p;
}

template <class Real>
void BasicSolver<Real>::prepare_fronts(Stage which, StagePlan& p, double dt) {
    if constexpr (kFronts) {
        // The tips of the stage's input (front.hpp).
        State& in = *p.in;
        front_->fill_ghosts(in.h, in.wet_fraction, mirrored_);
        if (which == Stage::predictor && state_changed_outside_) {  // the wet fraction may not match h: make it (idempotent)
            const std::vector<ColumnRange> all(std::size_t(grid_.ny), ColumnRange{0, grid_.nx});
            front_->fix(in.h, z_, all, in.wet_fraction, in.wet_fraction);
        }
        front_->find_tips(in.h, in.hu, in.hv, in.wet_fraction, z_, g_n2_, active_);
        // The wet fraction after the step grows with the predictor's tips (forward Euler: the
        // front is first order anyway; 1D trials gave the same fronts as Heun's average); each
        // stage's output then makes now_.wet_fraction so grown consistent with its depth, row
        // by row in the strip (front_->fix_row), into the output's wet fraction.
        if (!p.corrector) front_->grow(now_.wet_fraction, dt);
    }
}

template <class Real>
void BasicSolver<Real>::stage_strip(const StagePlan& p, Array& mem, int j0, int j1, long& fixes, Real& worst, Real& amax) {
    if (mem.size() != RowBuffers<Real>::kRows * stride_) mem.assign(RowBuffers<Real>::kRows * stride_, Real(0));
    const RowBuffers<Real> w(mem.data(), stride_);
    const Sweep<Real> s = sweep_constants();
    const StageRings<Real> rings(s, active_, *p.in, z_, p.fronts ? &*front_ : nullptr, w, stride_);
    State& out = *p.out;
    auto row = [&](Array& a, int j) { return padded::row(a, j, stride_); };
    if (j0 < j1) {
        for (int j = j0 - 2; j < j0 + 2; ++j) rings.primitives(j);
        for (int j = j0 - 1; j < j0 + 1; ++j) rings.slopes(j);
        rings.faces(j0);
    }
    for (int j = j0; j < j1; ++j) {
        rings.primitives(j + 2);
        rings.slopes(j + 1);
        rings.faces(j + 1);
        const ColumnRange cols = rings.active(j);
        // The output is exactly zero outside the columns computed now (as U^n is there
        // in the corrector: its nonzero cells are active).
        for (Array* a : {&out.h, &out.hu, &out.hv}) padded::clear_outside(row(*a, j), out.bound[std::size_t(j)], cols);
        face_mass_[0][std::size_t(j)] = face_mass_[1][std::size_t(j)] = 0.0;
        if (!cols.empty()) {
            const auto [west_mass, east_mass] = rates_row(s, cols, row(p.in->h, j), w, j + kGhost, rings.tips_of(j));
            face_mass_[0][std::size_t(j)] = west_mass;
            face_mass_[1][std::size_t(j)] = east_mass;
            update_stage_row(p, s, w, j, cols, fixes, worst, amax);
        }
        if (p.fronts)
            for (Side side : {Side::west, Side::east})
                fill_side_cells(side, p.out_forcing[std::size_t(side)], out.h, out.hu, out.hv, p.t_out, j, j + 1);
        // The wet fraction of the row below, whose neighbours are final now (the first
        // and last rows of the strip wait for the threads beside).
        if constexpr (kFronts)
            if (p.fronts && j - 1 > j0) front_->fix_row(out.h, z_, active_, now_.wet_fraction, out.wet_fraction, true, j - 1);
    }
}

// Row j's update from its rates (in w), the pump's source and friction; the output's CFL
// rate when this stage ends the step.
template <class Real>
void BasicSolver<Real>::update_stage_row(const StagePlan& p, const rows::Sweep<Real>& s, const rows::RowBuffers<Real>& w, int j,
                                         ColumnRange cols, long& fixes, Real& worst, Real& amax) {
    auto row = [&](Array& a) { return padded::row(a, j, stride_); };
    Real* dh = w.rate(0);
    const Real dt = Real(p.dt), pump_rate = Real(p.pump_rate);
    for (std::size_t k = pump_row_start_[std::size_t(j)]; p.pump_rate != 0.0 && k < pump_row_start_[std::size_t(j) + 1]; ++k)
        dh[pump_cells_[k] % stride_] += pump_rate;
    State &in = *p.in, &out = *p.out;
    if (p.corrector)
        update_row_with<Real, true>(fv_.friction, s, cols, dt, Real(0.5), row(in.h), row(in.hu), row(in.hv), w, row(g_n2_),
                                    row(now_.h), row(now_.hu), row(now_.hv), row(out.h), row(out.hu), row(out.hv), fixes, worst);
    else
        update_row_with<Real, false>(fv_.friction, s, cols, dt, Real(0), row(in.h), row(in.hu), row(in.hv), w, row(g_n2_),
                                     nullptr, nullptr, nullptr, row(out.h), row(out.hu), row(out.hv), fixes, worst);
    if (p.last) amax = std::max(amax, max_wave_rate_row(s, cols, row(out.h), row(out.hu), row(out.hv)));
}

template void BasicSolver<double>::stage(Stage, double, double);
template void BasicSolver<float>::stage(Stage, double, double);

}  // namespace flotsam::hydro
