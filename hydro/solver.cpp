#include "hydro/solver.hpp"

#include <omp.h>
#include <xmmintrin.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <utility>

#include "common/error.hpp"
#include "hydro/split_rows.hpp"
#include "hydro/swe_kernels.hpp"
#include "hydro/swe_rows.hpp"

namespace flotsam::hydro {

namespace {
using namespace rows;

// Flush subnormal numbers to zero on this thread. Friction shrinks discharges in thin
// films geometrically, into the subnormal range, where every operation costs ~100
// cycles; values below 1e-308 carry no physics.
inline void flush_subnormals() { _mm_setcsr(_mm_getcsr() | 0x8040); }
bool is_x_side(Side s) { return s == Side::west || s == Side::east; }
}  // namespace

Solver::Solver(const Scene& scene, const PhysicsDef& def, const FiniteVolumeDef& fv)
    : grid_(scene.grid),
      def_(def),
      fv_(fv),
      front_(scene.grid.nx, scene.grid.ny, scene.grid.dx, scene.grid.dy, def.gravity, def.dry_depth),
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
    for (auto* v : {&h_, &hu_, &hv_, &h1_, &hu1_, &hv1_, &h2_, &hu2_, &hv2_, &z_, &g_n2_, &alpha_, &alpha1_, &alpha2_})
        v->assign(n, 0.0);
    for (auto* v : {&bound_, &bound1_, &bound2_, &state_nonzero_, &base_nonzero_, &active_})
        v->assign(std::size_t(grid_.ny), ColumnRange{});
    depth_nonzero_.assign(rows_, ColumnRange{});

    for (int j = 0; j < grid_.ny; ++j)
        for (int i = 0; i < grid_.nx; ++i) {
            const std::size_t k = grid_.index(i, j), p = at(i, j);
            z_[p] = scene.z[k];
            const double n_manning = scene.manning_n.empty() ? def.default_manning_n : scene.manning_n[k];
            g_n2_[p] = def.gravity * n_manning * n_manning;
            const double eta0 = scene.eta0.empty() ? 0.0 : scene.eta0[k];
            const double h = std::max(0.0, eta0 - z_[p]);
            h_[p] = h;
            if (!scene.u0.empty() && h > 0.0) {
                hu_[p] = h * scene.u0[k];
                hv_[p] = h * scene.v0[k];
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
            rest_depth_[int(s)].push_back(xs ? h_[at(s == Side::west ? 0 : grid_.nx - 1, k)]
                                             : h_[at(k, s == Side::south ? 0 : grid_.ny - 1)]);
    }
    front_.reset(h_, alpha_);
    track_transfer_ = def.west.kind == BoundaryKind::nested || def.east.kind == BoundaryKind::nested;
    for (auto* v : {&west_face_mass_, &east_face_mass_, &west_stage1_, &east_stage1_, &west_transfer_, &east_transfer_})
        v->assign(std::size_t(grid_.ny), 0.0);
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
        for (int i = 0; i < grid_.nx; ++i) v += h_[at(i, j)];
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
    const double* depth = h_.data() + at(i0, j);
    const double* qx = hu_.data() + at(i0, j);
    const double* qy = hv_.data() + at(i0, j);
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
            const double* h = h_.data() + row;
            const double* hu = hu_.data() + row;
            const double* hv = hv_.data() + row;
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

SideForcing Solver::side_forcing(Side s, double t) {
    const SideForcing forcing = forcing_.at(s, t, [&] {
        double sum = 0.0;
        for (std::size_t p : pump_cells_) sum += h_[p] + z_[p];
        return sum / double(pump_cells_.size());
    });
    if (forcing.kind == BoundaryKind::nested) {
        const int n_along = is_x_side(s) ? grid_.ny : grid_.nx;
        if (nested_[s == Side::west ? 0 : 1].a.h.size() != std::size_t(kGhost * n_along))
            fail("", "boundary nested", "ghost values were not set before stepping");
    }
    return forcing;
}

void Solver::fill_side(Side s, std::vector<double>& h, std::vector<double>& hu, std::vector<double>& hv, double t) {
    fill_side_cells(s, side_forcing(s, t), h, hu, hv, t, 0, is_x_side(s) ? grid_.ny : grid_.nx);
}

void Solver::fill_side_cells(Side s, const SideForcing& forcing, std::vector<double>& h, std::vector<double>& hu,
                             std::vector<double>& hv, double t, int k0, int k1) const {
    const BoundaryKind kind = forcing.kind;
    const bool xs = is_x_side(s);
    const int n_along = xs ? grid_.ny : grid_.nx;
    if (kind == BoundaryKind::nested) {
        const NestedGhosts& ng = nested_[s == Side::west ? 0 : 1];
        const double w = ng.t1 > ng.t0 ? std::clamp((t - ng.t0) / (ng.t1 - ng.t0), 0.0, 1.0) : 0.0;
        for (int layer = 1; layer <= kGhost; ++layer)
            for (int k = k0; k < k1; ++k) {
                const std::size_t ghost = at(s == Side::west ? -layer : grid_.nx - 1 + layer, k);
                const std::size_t q = std::size_t((layer - 1) * n_along + k);
                h[ghost] = (1.0 - w) * ng.a.h[q] + w * ng.b.h[q];
                hu[ghost] = (1.0 - w) * ng.a.hu[q] + w * ng.b.hu[q];
                hv[ghost] = (1.0 - w) * ng.a.hv[q] + w * ng.b.hv[q];
            }
        return;
    }
    // Inward normal: +x at the west, -x at the east, +y at the south, -y at the north.
    const double sign = (s == Side::west || s == Side::south) ? 1.0 : -1.0;
    const double g = def_.gravity;
    for (int k = k0; k < k1; ++k) {
        auto cell = [&](int depth) {  // depth 0 = edge cell, 1 = next; -1, -2 = ghosts
            if (xs) return at(s == Side::west ? depth : grid_.nx - 1 - depth, k);
            return at(k, s == Side::south ? depth : grid_.ny - 1 - depth);
        };
        std::vector<double>& qn = xs ? hu : hv;  // normal discharge
        std::vector<double>& qt = xs ? hv : hu;  // tangential discharge
        for (int g_layer = 1; g_layer <= kGhost; ++g_layer) {
            const std::size_t ghost = cell(-g_layer);
            switch (kind) {
                case BoundaryKind::wall: {
                    const std::size_t src = cell(g_layer - 1);
                    h[ghost] = h[src];
                    qn[ghost] = -qn[src];
                    qt[ghost] = qt[src];
                    break;
                }
                case BoundaryKind::zero_gradient: {  // study only: lets inflow feed itself (docs/hydro.md)
                    const std::size_t src = cell(0);
                    h[ghost] = h[src];
                    qn[ghost] = qn[src];
                    qt[ghost] = qt[src];
                    break;
                }
                case BoundaryKind::transmissive:
                case BoundaryKind::level:
                case BoundaryKind::discharge: {
                    const std::size_t src = cell(0);
                    const double h_in = h[src];
                    const double un_in = sign * velocity(h_in, qn[src], def_.dry_depth);
                    const double ut_in = velocity(h_in, qt[src], def_.dry_depth);
                    const double h0 =
                        kind == BoundaryKind::transmissive ? rest_depth_[int(s)][std::size_t(k)] : std::max(0.0, -z_[src]);
                    double hb = 0.0, unb = 0.0;
                    open_side_state(forcing, h_in, un_in, h0, g, def_.dry_depth, hb, unb);
                    h[ghost] = hb;
                    qn[ghost] = sign * hb * unb;
                    qt[ghost] = hb * ut_in;
                    break;
                }
                case BoundaryKind::pump:
                case BoundaryKind::nested:
                    break;  // resolved above
            }
        }
    }
}

void Solver::fill_ghosts(std::vector<double>& h, std::vector<double>& hu, std::vector<double>& hv, double t) {
    for (Side s : {Side::west, Side::east, Side::south, Side::north}) fill_side(s, h, hu, hv, t);
}

namespace {

// ---- The fused stage ----
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
//
// Dry land: a cell whose depth is zero over its whole stencil (2 cells each way in x
// and y) has zero velocities (u = hu * 0) and depths at its faces, so every flux and
// rate of the cell is +0 or -0, whatever the discharges there. If its own h, hu, hv are
// +0 (all bits zero), its update then gives +0 again: the cell need not be computed.
// Per row, only the columns within 2 cells of a nonzero depth in the 5 rows around it,
// and those with a nonzero state, are (find_active_columns). This is exact, not a
// second dry tolerance: a film of 1e-9 m is computed like any water.

ColumnRange widen(ColumnRange a, int n) { return a.empty() ? a : ColumnRange{a.begin - n, a.end + n}; }
ColumnRange clip(ColumnRange a, int lo, int hi) { return {std::max(a.begin, lo), std::min(a.end, hi)}; }

bool is_zero(double x) { return std::bit_cast<std::uint64_t>(x) == 0; }  // +0 only

// Sets the cells of `was` outside `now` to zero.
void clear_outside(double* row, ColumnRange was, ColumnRange now) {
    if (was.empty()) return;
    if (now.empty()) now = {was.end, was.end};
    for (int i = was.begin; i < std::min(was.end, now.begin); ++i) row[i + kGhost] = 0.0;
    for (int i = std::max(was.begin, now.end); i < was.end; ++i) row[i + kGhost] = 0.0;
}

}  // namespace

void Solver::find_active_columns(Stage which, const std::vector<double>& h, const std::vector<double>& hu,
                                 const std::vector<double>& hv, bool pumping) {
    find_active_columns(which == Stage::corrector ? bound1_ : bound_, which == Stage::predictor && state_changed_outside_, h, hu, hv,
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

void Solver::find_active_columns(const std::vector<ColumnRange>& bound, bool whole_rows, const std::vector<double>& h,
                                 const std::vector<double>& hu, const std::vector<double>& hv, bool pumping) {
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
        auto depth_nonzero = [&](int i) { return h[at_column(i)] != 0.0; };
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

void Solver::stage(Stage which, double dt, double t) {
    const bool corrector = which == Stage::corrector;
    std::vector<double>& h = corrector ? h1_ : h_;
    std::vector<double>& hu = corrector ? hu1_ : hu_;
    std::vector<double>& hv = corrector ? hv1_ : hv_;
    // The corrector writes U^{n+1} into h2_, not over U^n: step_once swaps the two, and a
    // step redone for positivity (step) finds U^n in h2_ without a copy.
    std::vector<double>& h_out = corrector ? h2_ : h1_;
    std::vector<double>& hu_out = corrector ? hu2_ : hu1_;
    std::vector<double>& hv_out = corrector ? hv2_ : hv1_;
    const std::vector<ColumnRange>& out_bound = corrector ? bound2_ : bound1_;
    fill_ghosts(h, hu, hv, t);
    const double pump_rate = forcing_.pump_rate(t);  // [m/s] over the source strip
    const bool pumping = pump_rate != 0.0;
    find_active_columns(which, h, hu, hv, pumping);
    const bool last = corrector || fv_.order == 1;  // the step's result: remember its CFL rate
    const int nx = grid_.nx, ny = grid_.ny;
    const Sweep<double> s{
        def_.gravity, def_.dry_depth, fv_.limiter_theta, fv_.order == 2 ? 1.0 : 0.0, 1.0 / grid_.dx, 1.0 / grid_.dy, nx};
    auto active = [&](int j) { return j >= 0 && j < ny ? active_[std::size_t(j)] : ColumnRange{}; };
    // Fronts: the tips of the stage's input (front.hpp).
    std::vector<double>& alpha = corrector ? alpha1_ : alpha_;
    const bool fronts = fv_.fronts == FrontTreatment::tracked;
    if (fronts) {
        front_.fill_ghosts(h, alpha, mirrored_);
        if (which == Stage::predictor && state_changed_outside_) {  // alpha may not match h: make it (idempotent)
            const std::vector<ColumnRange> all(std::size_t(ny), ColumnRange{0, nx});
            front_.fix(h, z_, all, alpha, alpha);
        }
        front_.find_tips(h, hu, hv, alpha, z_, g_n2_, active_);
    }
    auto tips_of = [&](int j) -> const std::vector<Tip>* {
        if (!fronts || !front_.any_tips() || j < 0 || j >= ny) return nullptr;
        const std::vector<Tip>& row_tips = front_.tips(j);
        return row_tips.empty() ? nullptr : &row_tips;
    };
    auto row = [&](const std::vector<double>& a, int j) { return a.data() + std::size_t(j + kGhost) * stride_; };
    auto row_out = [&](std::vector<double>& a, int j) { return a.data() + std::size_t(j + kGhost) * stride_; };
    if (work_.size() < std::size_t(omp_get_max_threads())) work_.resize(std::size_t(omp_get_max_threads()));
    // Columns to compute in the rows below each row, to give each thread an equal share
    // (with dry land skipped, rows cost different amounts; up to 10 % on 2 threads).
    cumulative_columns_.assign(std::size_t(ny) + 1, 0.0);
    for (int j = 0; j < ny; ++j)
        cumulative_columns_[std::size_t(j) + 1] =
            cumulative_columns_[std::size_t(j)] + 1.0 + std::max(0, active(j).end - active(j).begin);
    // The wet fraction after the step grows with the predictor's tips (forward Euler: the
    // front is first order anyway; 1D trials gave the same fronts as Heun's average); each
    // stage's output then makes alpha_ so grown consistent with its depth, row by row in
    // the sweep (front_.fix_row), into alpha_out.
    if (fronts && !corrector) front_.grow(alpha_, dt);
    std::vector<double>& alpha_out = corrector ? alpha2_ : alpha1_;
    // The output's ghost cells, for its wet fraction's fix in the sweep: each row's x
    // ghosts once the row is updated, the y ghost rows after the sweep, at the output's
    // time, so that they are those the next stage fills in. Fixed against whatever the
    // buffer held from its last use instead, the edge cells' wet fraction depended on that
    // history, and a run that wrote checkpoints gave other bytes. The forcing is worked
    // out here, before the output exists: a pump that stops within this step takes its
    // level from the step's start (order 2: as the corrector's own fill would; order 1: a
    // step earlier than the next step's fill, which would read this output).
    std::array<SideForcing, 4> out_forcing{};
    const double t_out = corrector ? t : t + dt;
    if (fronts)
        for (Side side : {Side::west, Side::east, Side::south, Side::north})
            out_forcing[std::size_t(side)] = side_forcing(side, t_out);
    long fixes = 0;
    double worst = 0.0, amax = 0.0;
#pragma omp parallel reduction(+ : fixes) reduction(min : worst) reduction(max : amax)
    {
        flush_subnormals();
        const int nt = omp_get_num_threads(), tid = omp_get_thread_num();
        std::vector<double>& mem = work_[std::size_t(tid)];
        if (mem.size() != RowBuffers<double>::kRows * stride_) mem.assign(RowBuffers<double>::kRows * stride_, 0.0);
        const RowBuffers<double> w(mem.data(), stride_);
        // Each quantity of a row over the columns its users need (interior row j):
        // primitives for the slopes of rows j-1 .. j+1 and the x-sweep of row j;
        // y-slopes for the faces below and above row j and its bed slope; y-faces for
        // the rows on either side.
        auto primitives = [&](int j) {
            ColumnRange c = widen(active(j), 2);
            for (int k = j - 2; k <= j + 2; ++k) c = hull(c, active(k));
            c = clip(c, -kGhost, nx + kGhost);
            primitives_row(s, c, row(h, j), row(hu, j), row(hv, j), row(z_, j), w.prim(j + kGhost, 0), w.prim(j + kGhost, 1),
                           w.prim(j + kGhost, 2));
        };
        auto slopes = [&](int j) {
            const ColumnRange c = hull(hull(active(j - 1), active(j)), active(j + 1));
            y_slopes_row(s, c, row(h, j - 1), row(h, j), row(h, j + 1), w, j + kGhost);
            // First order at y-tips and their y-neighbours; a ghost row as the edge row it
            // mirrors (see x_slopes_at_tips).
            const int as_row = j == -1 ? 0 : (j == ny ? ny - 1 : j);
            for (int k = as_row - 1; k <= as_row + 1; ++k)
                if (const std::vector<Tip>* tips = tips_of(k))
                    for (const Tip& tip : *tips)
                        if (!is_x(tip.dir) && tip.i >= c.begin && tip.i < c.end)
                            for (int q = 0; q < 4; ++q) w.slope(j + kGhost, q)[tip.i + kGhost] = 0.0;
        };
        auto faces = [&](int j) {
            y_faces_row(s, hull(active(j - 1), active(j)), row(h, j - 1), row(h, j), w, j + kGhost);
            // The y faces of tips: the face below row j is the back face of a north-moving
            // tip in row j and of a south-moving one in row j - 1, the shut face of the others.
            const double *lo_e = w.prim(j - 1 + kGhost, 0), *hi_e = w.prim(j + kGhost, 0);
            const double *lo_u = w.prim(j - 1 + kGhost, 1), *hi_u = w.prim(j + kGhost, 1);
            const double *lo_h = row(h, j - 1), *hi_h = row(h, j);
            double *fm = w.face(j + kGhost, 0), *fl = w.face(j + kGhost, 1), *fr = w.face(j + kGhost, 2),
                   *ft = w.face(j + kGhost, 3);
            for (int k : {j - 1, j})
                if (const std::vector<Tip>* tips = tips_of(k))
                    for (const Tip& tip : *tips) {
                        if (is_x(tip.dir)) continue;
                        const int c = tip.i + kGhost;
                        const bool north = tip.dir == TipDir::north;
                        if (north == (k == j)) {
                            store(back_face_flux(s, tip.face, north ? 1.0 : -1.0, lo_u[c], hi_u[c]), c, fm, fl, fr, ft);
                        } else {
                            FaceFlux f;
                            shut_face_flux(lo_e[c], lo_h[c], hi_e[c], hi_h[c], s.g, f);
                            store(f, c, fm, fl, fr, ft);
                        }
                    }
        };
        // Rates and update of interior row j over its columns (nonempty).
        auto compute_row = [&](int j, ColumnRange cols) {
            const auto [west_mass, east_mass] = rates_row(s, cols, row(h, j), w, j + kGhost, tips_of(j));
            west_face_mass_[std::size_t(j)] = west_mass;
            east_face_mass_[std::size_t(j)] = east_mass;
            double* dh = w.rate(0);
            for (std::size_t k = pump_row_start_[std::size_t(j)]; pumping && k < pump_row_start_[std::size_t(j) + 1]; ++k)
                dh[pump_cells_[k] % stride_] += pump_rate;
            if (corrector)
                update_row_with<double, true>(fv_.friction, s, cols, dt, 0.5, row(h, j), row(hu, j), row(hv, j), w, row(g_n2_, j),
                                              row(h_, j), row(hu_, j), row(hv_, j), row_out(h_out, j), row_out(hu_out, j),
                                              row_out(hv_out, j), fixes, worst);
            else
                update_row_with<double, false>(fv_.friction, s, cols, dt, 0.0, row(h, j), row(hu, j), row(hv, j), w, row(g_n2_, j),
                                               nullptr, nullptr, nullptr, row_out(h_out, j), row_out(hu_out, j), row_out(hv_out, j),
                                               fixes, worst);
            if (last) amax = std::max(amax, max_wave_rate_row(s, cols, row(h_out, j), row(hu_out, j), row(hv_out, j)));
        };
        // This thread's strip of interior rows.
        auto first_row = [&](int k) {
            const double share = cumulative_columns_.back() * k / nt;
            return int(std::lower_bound(cumulative_columns_.begin(), cumulative_columns_.end(), share) -
                       cumulative_columns_.begin());
        };
        const int j0 = first_row(tid), j1 = tid + 1 == nt ? ny : first_row(tid + 1);
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
            // The output is exactly zero outside the columns computed now (as U^n is there
            // in the corrector: its nonzero cells are active).
            for (std::vector<double>* a : {&h_out, &hu_out, &hv_out})
                clear_outside(row_out(*a, j), out_bound[std::size_t(j)], cols);
            west_face_mass_[std::size_t(j)] = east_face_mass_[std::size_t(j)] = 0.0;
            if (!cols.empty()) compute_row(j, cols);
            if (fronts)
                for (Side side : {Side::west, Side::east})
                    fill_side_cells(side, out_forcing[std::size_t(side)], h_out, hu_out, hv_out, t_out, j, j + 1);
            // The wet fraction of the row below, whose neighbours are final now (the first
            // and last rows of the strip wait for the threads beside).
            if (fronts && j - 1 > j0) front_.fix_row(h_out, z_, active_, alpha_, alpha_out, true, j - 1);
        }
        if (fronts) {
#pragma omp barrier
#pragma omp single
            for (Side side : {Side::south, Side::north})
                fill_side_cells(side, out_forcing[std::size_t(side)], h_out, hu_out, hv_out, t_out, 0, nx);
            if (j0 < j1) front_.fix_row(h_out, z_, active_, alpha_, alpha_out, true, j0);
            if (j0 < j1 - 1) front_.fix_row(h_out, z_, active_, alpha_, alpha_out, true, j1 - 1);
        }
    }
    stats_.negative_depth_fixes += fixes;
    stats_.min_depth_seen = std::min(stats_.min_depth_seen, worst);
    (corrector ? bound2_ : bound1_) = active_;
    if (last) max_wave_rate_ = amax;
    if (fronts) front_.fix_done(h_out, active_, alpha_, alpha_out, true);
}

double Solver::add_side_depth(Side side, const std::vector<double>& dh, long& clamps) {
    if (!is_x_side(side) || dh.size() != std::size_t(grid_.ny))
        fail("", "nesting", "a side depth change of the wrong side or size");
    const int i = side == Side::west ? 0 : grid_.nx - 1;
    const std::ptrdiff_t inward = side == Side::west ? 1 : -1;
    const double dry = def_.dry_depth;
    const bool fronts = fv_.fronts == FrontTreatment::tracked;
    bool inside_water = true;  // every cell changed and its neighbour inward wet all over, and wet after
    double made = 0.0;
    bool rate_lost = false;  // a changed cell set the known rate and now has a lower one
    for (int j = 0; j < grid_.ny; ++j) {
        const std::size_t c = at(i, j);
        const double rate_before = cell_rate(h_[c], hu_[c], hv_[c]);
        h_[c] += dh[std::size_t(j)];
        if (h_[c] < 0.0) {
            made -= h_[c] * grid_.dx * grid_.dy;
            h_[c] = 0.0;
            ++clamps;
        }
        if (h_[c] != 0.0) bound_[std::size_t(j)] = hull(bound_[std::size_t(j)], {i, i + 1});
        // The rate known from the last step stays the state's largest if it covers the
        // changed cells and none of them set it (so that a restart, which computes it
        // afresh, takes the same steps).
        const double rate = cell_rate(h_[c], hu_[c], hv_[c]);
        rate_lost = rate_lost || (rate_before == max_wave_rate_ && rate < rate_before);
        if (max_wave_rate_ >= 0.0) max_wave_rate_ = std::max(max_wave_rate_, rate);
        if (dh[std::size_t(j)] != 0.0)
            inside_water =
                inside_water && h_[c] > dry && alpha_[c] == 1.0 && alpha_[std::size_t(std::ptrdiff_t(c) + inward)] == 1.0;
    }
    // Cells that stay inside the water keep a wet fraction of 1 (front.hpp). Beside a
    // front the fractions depend on the depths: the next step makes them consistent
    // over the whole slab, as after any change from outside.
    if (fronts && !inside_water) changed_outside(h_);
    if (rate_lost) max_wave_rate_ = -1.0;
    return made;
}

void Solver::set_nested_ghosts(Side side, double t0, const GhostState& a, double t1, const GhostState& b) {
    if (!is_x_side(side) || boundary(side).kind != BoundaryKind::nested)
        fail("", "boundary nested", "ghosts given for a side that is not nested");
    const std::size_t n = std::size_t(kGhost * grid_.ny);
    for (const GhostState* g : {&a, &b})
        if (g->h.size() != n || g->hu.size() != n || g->hv.size() != n)
            fail("", "boundary nested", "ghost arrays of the wrong size");
    NestedGhosts& ng = nested_[side == Side::west ? 0 : 1];
    ng.t0 = t0;
    ng.t1 = t1;
    ng.a = a;
    ng.b = b;
}

void Solver::set_ghost_bed(Side side, const std::vector<double>& z) {
    if (!is_x_side(side) || z.size() != std::size_t(kGhost * grid_.ny))
        fail("", "boundary nested", "ghost bed of the wrong size or side");
    for (int layer = 1; layer <= kGhost; ++layer)
        for (int j = 0; j < grid_.ny; ++j)
            z_[at(side == Side::west ? -layer : grid_.nx - 1 + layer, j)] = z[std::size_t((layer - 1) * grid_.ny + j)];
}

void Solver::reset_side_transfer() {
    std::fill(west_transfer_.begin(), west_transfer_.end(), 0.0);
    std::fill(east_transfer_.begin(), east_transfer_.end(), 0.0);
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
    saved_west_transfer_ = west_transfer_;
    saved_east_transfer_ = east_transfer_;
    step_once(dt);
    if (stats_.negative_depth_fixes == fixes_before) return;
    // Back to U^n, which step_once left in h2_ (second order; first order copies).
    if (fv_.order == 2 || fv_.stepping == TimeStepping::split) {
        h_.swap(h2_);
        hu_.swap(hu2_);
        hv_.swap(hv2_);
        bound_.swap(bound2_);
    } else {
        h_ = h2_;
        hu_ = hu2_;
        hv_ = hv2_;
    }
    alpha_.swap(alpha2_);
    if (fv_.stepping == TimeStepping::split) sweep_order_[0] = 1.0 - sweep_order_[0];  // the discarded step's toggle
    west_transfer_.swap(saved_west_transfer_);
    east_transfer_.swap(saved_east_transfer_);
    stats_.negative_depth_fixes = fixes_before;
    stats_.min_depth_seen = min_before;
    --stats_.steps;
    ++stats_.positivity_redos;
    state_changed_outside_ = true;  // bound_ describes the discarded state
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
            for (std::size_t j = 0; j < west_transfer_.size(); ++j) {
                west_transfer_[j] += dt * west_face_mass_[j];
                east_transfer_[j] += dt * east_face_mass_[j];
            }
        h2_.swap(h_);  // U^n, for a step redone for positivity
        hu2_.swap(hu_);
        hv2_.swap(hv_);
        h_ = h1_;
        hu_ = hu1_;
        hv_ = hv1_;
        bound_ = bound1_;
        alpha2_.swap(alpha_);
        alpha_ = alpha1_;
    } else {
        stage(Stage::predictor, dt, time_);
        if (track_transfer_) {
            west_stage1_ = west_face_mass_;
            east_stage1_ = east_face_mass_;
        }
        stage(Stage::corrector, dt, time_ + dt);
        // U^{n+1} (in h2_, nonzero within bound2_) becomes the state; U^n goes to h2_,
        // nonzero within bound_, or anywhere in a row if it was changed outside step().
        h_.swap(h2_);
        hu_.swap(hu2_);
        hv_.swap(hv2_);
        alpha_.swap(alpha2_);
        bound_.swap(bound2_);
        if (state_changed_outside_) std::fill(bound2_.begin(), bound2_.end(), ColumnRange{0, grid_.nx});
        if (track_transfer_)
            for (std::size_t j = 0; j < west_transfer_.size(); ++j) {
                west_transfer_[j] += 0.5 * dt * (west_stage1_[j] + west_face_mass_[j]);
                east_transfer_[j] += 0.5 * dt * (east_stage1_[j] + east_face_mass_[j]);
            }
    }
    if (fv_.fronts == FrontTreatment::tracked) {
        // The invariant correction (front.hpp) on the new state, which the last stage's
        // fix() saw (order 1: h1_, of which h_ is a copy); the step's CFL rate covers the
        // cells it changed.
        max_wave_rate_ = std::max(max_wave_rate_, front_.correct_invariants(h_, hu_, hv_, z_, g_n2_));
    }
    state_changed_outside_ = false;
    time_ += dt;
    ++stats_.steps;
}

// ---- The split step (split_rows.hpp) ----
//
// An x sweep and a y sweep, their order alternating from step to step; each sweep is
// one pass over the rows (the x sweep row by row, the y sweep with the ring buffers of
// the fused stage above), from h_ through h1_ into h2_, which then becomes the state
// (h2_ keeps U^n for a step redone for positivity). The second sweep applies the
// friction of the whole step. Ghosts are filled before each sweep at the half step.
void Solver::split_step(double dt) {
    const bool x_first = sweep_order_[0] == 0.0;
    const double t_half = time_ + 0.5 * dt;
    sweep(x_first ? Axis::x : Axis::y, false, dt, t_half, h_, hu_, hv_, bound_, state_changed_outside_, h1_, hu1_, hv1_, bound1_);
    sweep(x_first ? Axis::y : Axis::x, true, dt, t_half, h1_, hu1_, hv1_, bound1_, false, h2_, hu2_, hv2_, bound2_);
    h_.swap(h2_);
    hu_.swap(hu2_);
    hv_.swap(hv2_);
    bound_.swap(bound2_);
    if (state_changed_outside_) std::fill(bound2_.begin(), bound2_.end(), ColumnRange{0, grid_.nx});
    sweep_order_[0] = x_first ? 1.0 : 0.0;
}

void Solver::sweep(Axis axis, bool last, double dt, double t, std::vector<double>& h, std::vector<double>& hu,
                   std::vector<double>& hv, const std::vector<ColumnRange>& in_bound, bool whole_rows, std::vector<double>& h_out,
                   std::vector<double>& hu_out, std::vector<double>& hv_out, std::vector<ColumnRange>& out_bound) {
    fill_ghosts(h, hu, hv, t);
    const bool x_sweep = axis == Axis::x;
    // The pump's source goes with the x sweep (a depth [m] added after its update).
    const double pump_depth = x_sweep ? dt * forcing_.pump_rate(t) : 0.0;
    const bool pumping = pump_depth != 0.0;
    find_active_columns(in_bound, whole_rows, h, hu, hv, pumping);
    const int nx = grid_.nx, ny = grid_.ny;
    const Sweep<double> s{
        def_.gravity, def_.dry_depth, fv_.limiter_theta, fv_.order == 2 ? 1.0 : 0.0, 1.0 / grid_.dx, 1.0 / grid_.dy, nx};
    auto active = [&](int j) { return j >= 0 && j < ny ? active_[std::size_t(j)] : ColumnRange{}; };
    auto row = [&](const std::vector<double>& a, int j) { return a.data() + std::size_t(j + kGhost) * stride_; };
    auto row_out = [&](std::vector<double>& a, int j) { return a.data() + std::size_t(j + kGhost) * stride_; };
    if (work_.size() < std::size_t(omp_get_max_threads())) work_.resize(std::size_t(omp_get_max_threads()));
    cumulative_columns_.assign(std::size_t(ny) + 1, 0.0);
    for (int j = 0; j < ny; ++j)
        cumulative_columns_[std::size_t(j) + 1] =
            cumulative_columns_[std::size_t(j)] + 1.0 + std::max(0, active(j).end - active(j).begin);
    const double friction_dt = last ? dt : 0.0;
    const double hdt_y = 0.5 * dt / grid_.dy;
    long fixes = 0;
    double worst = 0.0, amax = 0.0;
#pragma omp parallel reduction(+ : fixes) reduction(min : worst) reduction(max : amax)
    {
        flush_subnormals();
        const int nt = omp_get_num_threads(), tid = omp_get_thread_num();
        std::vector<double>& mem = work_[std::size_t(tid)];
        if (mem.size() < split::Buffers<double>::kRows * stride_) mem.assign(split::Buffers<double>::kRows * stride_, 0.0);
        const split::Buffers<double> w(mem.data(), stride_);
        auto first_row = [&](int k) {
            const double share = cumulative_columns_.back() * k / nt;
            return int(std::lower_bound(cumulative_columns_.begin(), cumulative_columns_.end(), share) -
                       cumulative_columns_.begin());
        };
        const int j0 = first_row(tid), j1 = tid + 1 == nt ? ny : first_row(tid + 1);
        // The output is exactly zero outside the columns computed now.
        auto clear_row = [&](int j, ColumnRange cols) {
            for (std::vector<double>* a : {&h_out, &hu_out, &hv_out}) clear_outside(row_out(*a, j), out_bound[std::size_t(j)], cols);
        };
        auto add_pump = [&](int j) {
            for (std::size_t k = pump_row_start_[std::size_t(j)]; pumping && k < pump_row_start_[std::size_t(j) + 1]; ++k)
                h_out[pump_cells_[k]] += pump_depth;
        };
        if (x_sweep) {
            for (int j = j0; j < j1; ++j) {
                const ColumnRange cols = active(j);
                clear_row(j, cols);
                west_face_mass_[std::size_t(j)] = east_face_mass_[std::size_t(j)] = 0.0;
                if (cols.empty()) continue;
                auto run = [&]<bool kFriction, bool kRate>() {
                    return split::x_row<double, kFriction, kRate>(s, cols, dt, friction_dt, row(h, j), row(hu, j), row(hv, j),
                                                                  row(z_, j), row(g_n2_, j), w, row_out(h_out, j),
                                                                  row_out(hu_out, j), row_out(hv_out, j), fixes, worst, amax);
                };
                const auto [west_mass, east_mass] = last ? run.template operator()<true, true>() : run.template operator()<false, false>();
                west_face_mass_[std::size_t(j)] = west_mass;
                east_face_mass_[std::size_t(j)] = east_mass;
                add_pump(j);
            }
        } else {
            // Row j's update needs the primitives of rows j-2 .. j+2, the slopes and
            // predictor of rows j-1 .. j+1 and the faces below rows j and j+1, over its
            // columns; each ring row is computed over the columns its users need.
            auto primitives = [&](int j) {
                ColumnRange c = widen(active(j), 2);
                for (int k = j - 2; k <= j + 2; ++k) c = hull(c, active(k));
                c = clip(c, -kGhost, nx + kGhost);
                split::y_primitives_row(s, c.begin + kGhost, c.end + kGhost, row(h, j), row(hu, j), row(hv, j), row(z_, j), w,
                                        j + kGhost);
            };
            auto slopes = [&](int j) {
                const ColumnRange c = hull(hull(active(j - 1), active(j)), active(j + 1));
                split::y_slopes_row(s, c.begin + kGhost, c.end + kGhost, hdt_y, row(h, j - 1), row(h, j), row(h, j + 1), w,
                                    j + kGhost);
            };
            auto faces = [&](int j) {
                const ColumnRange c = hull(active(j - 1), active(j));
                split::y_faces_row(s, c.begin + kGhost, c.end + kGhost, row(h, j - 1), row(h, j), w, j + kGhost);
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
                clear_row(j, cols);
                if (cols.empty()) continue;
                if (last)
                    split::y_update_row<double, true, true>(s, cols, dt, friction_dt, row(h, j), row(hu, j), row(hv, j),
                                                            row(g_n2_, j), w, j + kGhost, row_out(h_out, j), row_out(hu_out, j),
                                                            row_out(hv_out, j), fixes, worst, amax);
                else
                    split::y_update_row<double, false, false>(s, cols, dt, friction_dt, row(h, j), row(hu, j), row(hv, j),
                                                              row(g_n2_, j), w, j + kGhost, row_out(h_out, j), row_out(hu_out, j),
                                                              row_out(hv_out, j), fixes, worst, amax);
            }
        }
    }
    if (x_sweep && track_transfer_)
        for (std::size_t j = 0; j < west_transfer_.size(); ++j) {
            west_transfer_[j] += dt * west_face_mass_[j];
            east_transfer_[j] += dt * east_face_mass_[j];
        }
    stats_.negative_depth_fixes += fixes;
    stats_.min_depth_seen = std::min(stats_.min_depth_seen, worst);
    out_bound = active_;
    if (last) {
        // The pump cells' rate after the source (the update's rate saw them before it).
        for (std::size_t p : pump_cells_)
            if (pumping) amax = std::max(amax, cell_rate(h_out[p], hu_out[p], hv_out[p]));
        max_wave_rate_ = amax;
    }
}

}  // namespace flotsam::hydro
