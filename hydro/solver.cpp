#include "hydro/solver.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "common/error.hpp"
#include "hydro/padded_rows.hpp"
#include "hydro/split_rows.hpp"
#include "hydro/swe_kernels.hpp"

namespace flotsam::hydro {

using padded::is_x_side;

template <class Real>
BasicSolver<Real>::BasicSolver(const Scene& scene, const PhysicsDef& def, const FiniteVolumeDef& fv)
    : grid_(scene.grid),
      def_(def),
      fv_(fv),
      forcing_({def.west, def.east, def.south, def.north}, def.pump, scene.grid, scene.z) {
    check_definition();
    allocate();
    set_initial_state(scene);
    fill_ghost_bed();
    record_rest_depths();
    place_pump_cells();
}

template <class Real>
void BasicSolver<Real>::check_definition() const {
    if (fv_.order != 1 && fv_.order != 2) fail("", "--order", "must be 1 or 2");
    if (!(fv_.cfl > 0.0 && (fv_.cfl <= 1.0 || def_.study_past_stability_limit)))
        fail("", "--cfl",
             "must be in (0, 1] (the scheme's linear stability limit is 1; above 0.5 steps are checked for positivity)");
    if (!(def_.dry_depth > 0.0)) fail("", "--dry-depth", "must be positive");
    if (fv_.stepping == TimeStepping::split && fv_.fronts == FrontTreatment::tracked)
        fail("", "--fronts", "tracked fronts are written for --time-stepping heun; the split step has plain fronts");
    if (fv_.stepping == TimeStepping::split && fv_.friction == Friction::explicit_)
        fail("", "--friction", "explicit friction (the stability study's) is written for --time-stepping heun");
    if (!kFronts && fv_.fronts == FrontTreatment::tracked)
        fail("", "--fronts", "tracked fronts are written for --precision float64");
}

template <class Real>
void BasicSolver<Real>::allocate() {
    stride_ = std::size_t(grid_.nx + 2 * kGhost);
    rows_ = std::size_t(grid_.ny + 2 * kGhost);
    const std::size_t n = stride_ * rows_;
    const bool fronts = fv_.fronts == FrontTreatment::tracked;
    if constexpr (kFronts)
        if (fronts) front_.emplace(grid_.nx, grid_.ny, grid_.dx, grid_.dy, def_.gravity, def_.dry_depth);
    for (State* g : {&now_, &mid_, &next_}) {
        for (Array* v : {&g->h, &g->hu, &g->hv}) v->assign(n, Real(0));
        if (fronts) g->wet_fraction.assign(n, Real(0));
        g->bound.assign(std::size_t(grid_.ny), ColumnRange{});
    }
    for (Array* v : {&z_, &g_n2_}) v->assign(n, Real(0));
    for (auto* v : {&state_nonzero_, &base_nonzero_, &active_}) v->assign(std::size_t(grid_.ny), ColumnRange{});
    depth_nonzero_.assign(rows_, ColumnRange{});
    track_transfer_ = def_.west.kind == BoundaryKind::nested || def_.east.kind == BoundaryKind::nested;
    for (auto* pair : {&face_mass_, &stage1_mass_, &transfer_})
        for (auto& v : *pair) v.assign(std::size_t(grid_.ny), 0.0);
}

// The scene's ground, friction and initial state. The depth is rounded to Real from the
// level over the ground as Real holds it, so that a lake at rest at level 0 has
// h + z = 0 exactly in either precision.
template <class Real>
void BasicSolver<Real>::set_initial_state(const Scene& scene) {
    for (int j = 0; j < grid_.ny; ++j)
        for (int i = 0; i < grid_.nx; ++i) {
            const std::size_t k = grid_.index(i, j), p = at(i, j);
            z_[p] = Real(scene.z[k]);
            const double n_manning = scene.manning_n.empty() ? def_.default_manning_n : scene.manning_n[k];
            g_n2_[p] = Real(def_.gravity * n_manning * n_manning);
            const double eta0 = scene.eta0.empty() ? 0.0 : scene.eta0[k];
            const Real h = Real(std::max(0.0, eta0 - double(z_[p])));
            now_.h[p] = h;
            if (!scene.u0.empty() && h > 0) {
                now_.hu[p] = Real(double(h) * scene.u0[k]);
                now_.hv[p] = Real(double(h) * scene.v0[k]);
            }
        }
    if constexpr (kFronts)
        if (front_) front_->reset(now_.h, now_.wet_fraction);
}

// Bed in the ghost cells: mirrored at walls (a lake at rest stays exact), copied elsewhere.
template <class Real>
void BasicSolver<Real>::fill_ghost_bed() {
    for (Side s : {Side::west, Side::east, Side::south, Side::north}) {
        mirrored_[int(s)] = boundary(s).kind == BoundaryKind::wall || boundary(s).kind == BoundaryKind::pump;
        const bool mirror = mirrored_[int(s)];
        if (is_x_side(s)) {
            for (int j = 0; j < grid_.ny; ++j)
                for (int g = 1; g <= kGhost; ++g) {
                    const int ig = s == Side::west ? -g : grid_.nx - 1 + g;
                    const int isrc = s == Side::west ? (mirror ? g - 1 : 0) : (mirror ? grid_.nx - g : grid_.nx - 1);
                    z_[at(ig, j)] = z_[at(isrc, j)];
                }
        } else {
            for (int i = 0; i < grid_.nx; ++i)
                for (int g = 1; g <= kGhost; ++g) {
                    const int jg = s == Side::south ? -g : grid_.ny - 1 + g;
                    const int jsrc = s == Side::south ? (mirror ? g - 1 : 0) : (mirror ? grid_.ny - g : grid_.ny - 1);
                    z_[at(i, jg)] = z_[at(i, jsrc)];
                }
        }
    }
}

// Each side's initial edge depths: the still water a transmissive side lets waves leave
// into (the leap-frog keeps the same).
template <class Real>
void BasicSolver<Real>::record_rest_depths() {
    for (Side s : {Side::west, Side::east, Side::south, Side::north}) {
        const bool xs = is_x_side(s);
        for (int k = 0; k < (xs ? grid_.ny : grid_.nx); ++k)
            rest_depth_[int(s)].push_back(xs ? now_.h[at(s == Side::west ? 0 : grid_.nx - 1, k)]
                                             : now_.h[at(k, s == Side::south ? 0 : grid_.ny - 1)]);
    }
}

// The pump's strip (Forcing places it, row by row) as padded indices with row starts.
template <class Real>
void BasicSolver<Real>::place_pump_cells() {
    for (auto [i, j] : forcing_.pump_cells()) {
        while (pump_row_start_.size() <= std::size_t(j)) pump_row_start_.push_back(pump_cells_.size());
        pump_cells_.push_back(at(i, j));
    }
    pump_row_start_.resize(std::size_t(grid_.ny) + 1, pump_cells_.size());
}

template <class Real>
const BoundaryDef& BasicSolver<Real>::boundary(Side s) const {
    switch (s) {
        case Side::west:
            return def_.west;
        case Side::east:
            return def_.east;
        case Side::south:
            return def_.south;
        case Side::north:
            return def_.north;
    }
    return def_.west;
}

template <class Real>
double BasicSolver<Real>::volume() const {
    double v = 0.0;  // serial: the same sum whatever the thread count
    for (int j = 0; j < grid_.ny; ++j)
        for (int i = 0; i < grid_.nx; ++i) v += now_.h[at(i, j)];
    return v * grid_.dx * grid_.dy;
}

template <class Real>
std::string BasicSolver<Real>::description() const {
    return std::string(fv_.stepping == TimeStepping::split
                           ? "finite volumes, MUSCL-Hancock in alternating x and y sweeps + hydrostatic reconstruction + HLL, "
                           : "finite volumes, MUSCL + hydrostatic reconstruction + HLL, Heun, ") +
           (fv_.friction == Friction::implicit ? "implicit Manning" : "explicit Manning (stability study only)") +
           (fv_.fronts == FrontTreatment::tracked ? ", tracked fronts" : ", plain fronts") +
           (precision == Precision::float32 ? ", float32 state" : "");
}

template <class Real>
void BasicSolver<Real>::state_row(int j, int i0, int i1, double* __restrict h, double* __restrict u, double* __restrict v) const {
    const Real* depth = now_.h.data() + at(i0, j);
    const Real* qx = now_.hu.data() + at(i0, j);
    const Real* qy = now_.hv.data() + at(i0, j);
    const Real dry = Real(def_.dry_depth);
#pragma omp simd
    for (int k = 0; k < i1 - i0; ++k) {
        h[k] = depth[k];
        u[k] = velocity(depth[k], qx[k], dry);
        v[k] = velocity(depth[k], qy[k], dry);
    }
}

template <class Real>
double BasicSolver<Real>::stable_dt() const {
    // Known from the last step unless the state was changed since.
    if (max_wave_rate_ < 0.0) {
        const Real g = Real(def_.gravity), dry = Real(def_.dry_depth), idx = Real(1.0 / grid_.dx), idy = Real(1.0 / grid_.dy);
        Real amax = 0;
        const bool split_step = fv_.stepping == TimeStepping::split;
#pragma omp parallel for reduction(max : amax) schedule(static)
        for (int j = 0; j < grid_.ny; ++j) {
            const std::size_t row = at(0, j);
            const Real* h = now_.h.data() + row;
            const Real* hu = now_.hu.data() + row;
            const Real* hv = now_.hv.data() + row;
            Real a = 0;
            if (split_step) {
#pragma omp simd reduction(max : a)
                for (int i = 0; i < grid_.nx; ++i) a = std::max(a, split::directional_wave_rate(h[i], hu[i], hv[i], g, dry, idx, idy));
            } else {
#pragma omp simd reduction(max : a)
                for (int i = 0; i < grid_.nx; ++i) a = std::max(a, wave_rate(h[i], hu[i], hv[i], g, dry, idx, idy));
            }
            amax = std::max(amax, a);
        }
        max_wave_rate_ = amax;
    }
    return max_wave_rate_ > 0.0 ? std::min(def_.max_dt, fv_.cfl / max_wave_rate_) : def_.max_dt;
}

template <class Real>
double BasicSolver<Real>::cell_rate(Real h, Real hu, Real hv) const {
    const Real g = Real(def_.gravity), dry = Real(def_.dry_depth), idx = Real(1.0 / grid_.dx), idy = Real(1.0 / grid_.dy);
    return fv_.stepping == TimeStepping::split ? split::directional_wave_rate(h, hu, hv, g, dry, idx, idy)
                                               : wave_rate(h, hu, hv, g, dry, idx, idy);
}

template <class Real>
rows::Sweep<Real> BasicSolver<Real>::sweep_constants() const {
    return {Real(def_.gravity), Real(def_.dry_depth), Real(fv_.limiter_theta), fv_.order == 2 ? Real(1) : Real(0),
            Real(1.0 / grid_.dx),  Real(1.0 / grid_.dy), grid_.nx};
}

template <class Real>
void BasicSolver<Real>::reset_side_transfer() {
    std::fill(transfer_[0].begin(), transfer_[0].end(), 0.0);
    std::fill(transfer_[1].begin(), transfer_[1].end(), 0.0);
}

template <class Real>
void BasicSolver<Real>::add_transfer(double weight) {
    if (!track_transfer_) return;
    for (std::size_t j = 0; j < transfer_[0].size(); ++j) {
        transfer_[0][j] += weight * face_mass_[0][j];
        transfer_[1][j] += weight * face_mass_[1][j];
    }
}

// Above cfl 0.5 (the positivity bound of each Euler stage) a step may drive a depth
// negative, mostly where a thin layer drains; it is then redone from the saved state in
// ceil(cfl / 0.45) equal steps, each within the bound. The redo is decided by an integer
// count, so the result does not depend on the thread count.
template <class Real>
void BasicSolver<Real>::step(double dt) {
    constexpr double kPositiveCfl = 0.5, kSafeCfl = 0.45;
    if (fv_.cfl <= kPositiveCfl || def_.study_past_stability_limit) {
        step_once(dt);
        return;
    }
    const double t0 = time_;
    const long fixes_before = stats_.negative_depth_fixes;
    const double min_before = stats_.min_depth_seen;
    saved_transfer_[0] = transfer_[0];
    saved_transfer_[1] = transfer_[1];
    step_once(dt);
    if (stats_.negative_depth_fixes == fixes_before) return;
    // Back to U^n, which step_once left in next_.
    now_.swap(next_);
    if (fv_.stepping == TimeStepping::split) sweep_order_[0] = 1.0 - sweep_order_[0];  // the discarded step's toggle
    transfer_[0].swap(saved_transfer_[0]);
    transfer_[1].swap(saved_transfer_[1]);
    stats_.negative_depth_fixes = fixes_before;
    stats_.min_depth_seen = min_before;
    --stats_.steps;
    ++stats_.positivity_redos;
    state_changed_outside_ = true;  // now_.bound describes the discarded state
    time_ = t0;
    const int n = int(std::ceil(fv_.cfl / kSafeCfl));
    for (int k = 0; k < n; ++k) step_once(dt / n);
    time_ = t0 + dt;
}

template <class Real>
void BasicSolver<Real>::step_once(double dt) {
    if (fv_.stepping == TimeStepping::split) {
        split_step(dt);
    } else if (fv_.order == 1) {
        // Boundary mass transfer with the stepper's weights: forward Euler's dt L(U^n).
        stage(Stage::predictor, dt, time_);
        add_transfer(dt);
        next_.swap(now_);  // U^n, for a step redone for positivity
        now_ = mid_;
    } else {
        // Heun's U^{n+1} = U^n + dt/2 (L(U^n) + L(U^1)).
        stage(Stage::predictor, dt, time_);
        if (track_transfer_) {
            stage1_mass_[0] = face_mass_[0];
            stage1_mass_[1] = face_mass_[1];
        }
        stage(Stage::corrector, dt, time_ + dt);
        // U^{n+1} (in next_) becomes the state; U^n goes to next_, nonzero within its bound,
        // or anywhere in a row if it was changed outside step().
        now_.swap(next_);
        if (state_changed_outside_) std::fill(next_.bound.begin(), next_.bound.end(), ColumnRange{0, grid_.nx});
        if (track_transfer_)
            for (std::size_t j = 0; j < transfer_[0].size(); ++j) {
                transfer_[0][j] += 0.5 * dt * (stage1_mass_[0][j] + face_mass_[0][j]);
                transfer_[1][j] += 0.5 * dt * (stage1_mass_[1][j] + face_mass_[1][j]);
            }
    }
    if constexpr (kFronts)
        if (fv_.fronts == FrontTreatment::tracked) {
            // The invariant correction (front.hpp) on the new state, which the last stage's
            // fix() saw (order 1: mid_.h, of which now_.h is a copy); the step's CFL rate covers
            // the cells it changed.
            max_wave_rate_ = std::max(max_wave_rate_, front_->correct_invariants(now_.h, now_.hu, now_.hv, z_, g_n2_));
        }
    state_changed_outside_ = false;
    time_ += dt;
    ++stats_.steps;
}

template class BasicSolver<double>;
template class BasicSolver<float>;

}  // namespace flotsam::hydro
