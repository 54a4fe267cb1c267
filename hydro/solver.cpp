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

Solver::Solver(const Scene& scene, const PhysicsDef& def, const FiniteVolumeDef& fv)
    : grid_(scene.grid),
      def_(def),
      fv_(fv),
      forcing_({def.west, def.east, def.south, def.north}, def.pump, scene.grid, scene.z) {
    if (fv.order != 1 && fv.order != 2) fail("", "--order", "must be 1 or 2");
    if (!(fv.cfl > 0.0 && (fv.cfl <= 1.0 || def.study_past_stability_limit)))
        fail("", "--cfl",
             "must be in (0, 1] (the scheme's linear stability limit is 1; above 0.5 steps are checked for positivity)");
    if (!(def.dry_depth > 0.0)) fail("", "--dry-depth", "must be positive");
    if (fv.stepping == TimeStepping::split && fv.fronts == FrontTreatment::tracked)
        fail("", "--fronts", "tracked fronts are written for --time-stepping heun; the split step has plain fronts");
    if (fv.stepping == TimeStepping::split && fv.friction == Friction::explicit_)
        fail("", "--friction", "explicit friction (the stability study's) is written for --time-stepping heun");
    stride_ = std::size_t(grid_.nx + 2 * kGhost);
    rows_ = std::size_t(grid_.ny + 2 * kGhost);
    const std::size_t n = stride_ * rows_;
    const bool fronts = fv.fronts == FrontTreatment::tracked;
    if (fronts) front_.emplace(scene.grid.nx, scene.grid.ny, scene.grid.dx, scene.grid.dy, def.gravity, def.dry_depth);
    for (GridState* g : {&now_, &mid_, &next_}) {
        for (auto* v : {&g->h, &g->hu, &g->hv}) v->assign(n, 0.0);
        if (fronts) g->wet_fraction.assign(n, 0.0);
        g->bound.assign(std::size_t(grid_.ny), ColumnRange{});
    }
    for (auto* v : {&z_, &g_n2_}) v->assign(n, 0.0);
    for (auto* v : {&state_nonzero_, &base_nonzero_, &active_}) v->assign(std::size_t(grid_.ny), ColumnRange{});
    depth_nonzero_.assign(rows_, ColumnRange{});

    for (int j = 0; j < grid_.ny; ++j)
        for (int i = 0; i < grid_.nx; ++i) {
            const std::size_t k = grid_.index(i, j), p = at(i, j);
            z_[p] = scene.z[k];
            const double n_manning = scene.manning_n.empty() ? def.default_manning_n : scene.manning_n[k];
            g_n2_[p] = def.gravity * n_manning * n_manning;
            const double eta0 = scene.eta0.empty() ? 0.0 : scene.eta0[k];
            const double h = std::max(0.0, eta0 - z_[p]);
            now_.h[p] = h;
            if (!scene.u0.empty() && h > 0.0) {
                now_.hu[p] = h * scene.u0[k];
                now_.hv[p] = h * scene.v0[k];
            }
        }
    // Bed in the ghost cells: mirrored at walls (a lake at rest stays exact), copied elsewhere.
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
    // Each side's initial edge depths: the still water a transmissive side lets waves
    // leave into (the leap-frog keeps the same).
    for (Side s : {Side::west, Side::east, Side::south, Side::north}) {
        const bool xs = is_x_side(s);
        for (int k = 0; k < (xs ? grid_.ny : grid_.nx); ++k)
            rest_depth_[int(s)].push_back(xs ? now_.h[at(s == Side::west ? 0 : grid_.nx - 1, k)]
                                             : now_.h[at(k, s == Side::south ? 0 : grid_.ny - 1)]);
    }
    if (fronts) front_->reset(now_.h, now_.wet_fraction);
    track_transfer_ = def.west.kind == BoundaryKind::nested || def.east.kind == BoundaryKind::nested;
    for (auto* pair : {&face_mass_, &stage1_mass_, &transfer_})
        for (auto& v : *pair) v.assign(std::size_t(grid_.ny), 0.0);
    // The pump's strip (Forcing places it, row by row) as padded indices with row starts.
    for (auto [i, j] : forcing_.pump_cells()) {
        while (pump_row_start_.size() <= std::size_t(j)) pump_row_start_.push_back(pump_cells_.size());
        pump_cells_.push_back(at(i, j));
    }
    pump_row_start_.resize(std::size_t(grid_.ny) + 1, pump_cells_.size());
}

const BoundaryDef& Solver::boundary(Side s) const {
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

double Solver::volume() const {
    double v = 0.0;  // serial: the same sum whatever the thread count
    for (int j = 0; j < grid_.ny; ++j)
        for (int i = 0; i < grid_.nx; ++i) v += now_.h[at(i, j)];
    return v * grid_.dx * grid_.dy;
}

std::string Solver::description() const {
    return std::string(fv_.stepping == TimeStepping::split
                           ? "finite volumes, MUSCL-Hancock in alternating x and y sweeps + hydrostatic reconstruction + HLL, "
                           : "finite volumes, MUSCL + hydrostatic reconstruction + HLL, Heun, ") +
           (fv_.friction == Friction::implicit ? "implicit Manning" : "explicit Manning (stability study only)") +
           (fv_.fronts == FrontTreatment::tracked ? ", tracked fronts" : ", plain fronts");
}

void Solver::state_row(int j, int i0, int i1, double* __restrict h, double* __restrict u, double* __restrict v) const {
    const double* depth = now_.h.data() + at(i0, j);
    const double* qx = now_.hu.data() + at(i0, j);
    const double* qy = now_.hv.data() + at(i0, j);
    const double dry = def_.dry_depth;
#pragma omp simd
    for (int k = 0; k < i1 - i0; ++k) {
        h[k] = depth[k];
        u[k] = velocity(depth[k], qx[k], dry);
        v[k] = velocity(depth[k], qy[k], dry);
    }
}

double Solver::stable_dt() const {
    // Known from the last step unless the state was changed since.
    if (max_wave_rate_ < 0.0) {
        const double g = def_.gravity, dry = def_.dry_depth, idx = 1.0 / grid_.dx, idy = 1.0 / grid_.dy;
        double amax = 0.0;
#pragma omp parallel for reduction(max : amax) schedule(static)
        for (int j = 0; j < grid_.ny; ++j) {
            const std::size_t row = at(0, j);
            const double* h = now_.h.data() + row;
            const double* hu = now_.hu.data() + row;
            const double* hv = now_.hv.data() + row;
            double a = 0.0;
            if (fv_.stepping == TimeStepping::split) {
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

double Solver::cell_rate(double h, double hu, double hv) const {
    const double g = def_.gravity, dry = def_.dry_depth, idx = 1.0 / grid_.dx, idy = 1.0 / grid_.dy;
    return fv_.stepping == TimeStepping::split ? split::directional_wave_rate(h, hu, hv, g, dry, idx, idy)
                                               : wave_rate(h, hu, hv, g, dry, idx, idy);
}

void Solver::reset_side_transfer() {
    std::fill(transfer_[0].begin(), transfer_[0].end(), 0.0);
    std::fill(transfer_[1].begin(), transfer_[1].end(), 0.0);
}

// Above cfl 0.5 (the positivity bound of each Euler stage) a step may drive a depth
// negative, mostly where a thin layer drains; it is then redone from the saved state in
// ceil(cfl / 0.45) equal steps, each within the bound. The redo is decided by an integer
// count, so the result does not depend on the thread count.
void Solver::step(double dt) {
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

void Solver::step_once(double dt) {
    if (fv_.stepping == TimeStepping::split) {
        split_step(dt);
        state_changed_outside_ = false;
        time_ += dt;
        ++stats_.steps;
        return;
    }
    // Boundary mass transfer with the stepper's weights: Heun's U^{n+1} = U^n + dt/2 (L(U^n) + L(U^1)).
    if (fv_.order == 1) {
        stage(Stage::predictor, dt, time_);
        if (track_transfer_)
            for (std::size_t j = 0; j < transfer_[0].size(); ++j) {
                transfer_[0][j] += dt * face_mass_[0][j];
                transfer_[1][j] += dt * face_mass_[1][j];
            }
        next_.swap(now_);  // U^n, for a step redone for positivity
        now_ = mid_;
    } else {
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
    if (fv_.fronts == FrontTreatment::tracked) {
        // The invariant correction (front.hpp) on the new state, which the last stage's
        // fix() saw (order 1: mid_.h, of which now_.h is a copy); the step's CFL rate covers the
        // cells it changed.
        max_wave_rate_ = std::max(max_wave_rate_, front_->correct_invariants(now_.h, now_.hu, now_.hv, z_, g_n2_));
    }
    state_changed_outside_ = false;
    time_ += dt;
    ++stats_.steps;
}

}  // namespace flotsam::hydro
