#include "hydro/nesting.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace flotsam::hydro {

NestDef default_nest_def() { return NestDef{}; }

namespace {
constexpr int kLayers = 2;  // ghost layers of hydro::Solver

int snapped_interface(const Scene& s, const NestDef& n) {
    if (n.ratio < 2) fail(s.path, "--nest-ratio", "must be 2 or more for a nested run");
    const int i = int(std::floor((n.x - s.grid.x_min_edge()) / s.grid.dx + 1e-9));
    const int snapped = (i / n.ratio) * n.ratio;
    if (snapped < 2 * n.ratio || s.grid.nx - snapped < 2 * n.ratio)
        fail(s.path, "--nest-x", "the interface must leave at least 2 coarse and " + std::to_string(2 * n.ratio) + " fine columns");
    return snapped;
}

}  // namespace

int rows_ratio(int rows, int ratio) {
    int r = std::min(ratio, rows);
    while (rows % r != 0) --r;
    return r;
}

namespace {

// Block averages (rx x ry cells) of the scene west of the interface.
Scene coarse_scene(const Scene& s, int rx, int ry, int i_nest) {
    Scene c;
    c.path = s.path;
    c.grid.nx = i_nest / rx;
    c.grid.ny = s.grid.ny / ry;
    c.grid.dx = s.grid.dx * rx;
    c.grid.dy = s.grid.dy * ry;
    c.grid.x0 = s.grid.x0 + 0.5 * (rx - 1) * s.grid.dx;
    c.grid.y0 = s.grid.y0 + 0.5 * (ry - 1) * s.grid.dy;
    auto average = [&](const std::vector<double>& f) {
        std::vector<double> out;
        if (f.empty()) return out;
        out.assign(c.grid.size(), 0.0);
        for (int J = 0; J < c.grid.ny; ++J)
            for (int I = 0; I < c.grid.nx; ++I) {
                double sum = 0.0;
                for (int b = 0; b < ry; ++b)
                    for (int a = 0; a < rx; ++a) sum += f[s.grid.index(I * rx + a, J * ry + b)];
                out[c.grid.index(I, J)] = sum / double(rx * ry);
            }
        return out;
    };
    c.z = average(s.z);
    c.manning_n = average(s.manning_n);
    c.eta0 = average(s.eta0);
    c.u0 = average(s.u0);
    c.v0 = average(s.v0);
    return c;
}

// The scene east of the interface, cell for cell.
Scene fine_scene(const Scene& s, int i_nest) {
    Scene f;
    f.path = s.path;
    f.grid = s.grid;
    f.grid.nx = s.grid.nx - i_nest;
    f.grid.x0 = s.grid.x(i_nest);
    auto crop = [&](const auto& v) {
        std::remove_cvref_t<decltype(v)> out;
        if (v.empty()) return out;
        out.reserve(f.grid.size());
        for (int j = 0; j < f.grid.ny; ++j)
            for (int i = 0; i < f.grid.nx; ++i) out.push_back(v[s.grid.index(i + i_nest, j)]);
        return out;
    };
    f.z = crop(s.z);
    f.manning_n = crop(s.manning_n);
    f.building = crop(s.building);
    f.eta0 = crop(s.eta0);
    f.u0 = crop(s.u0);
    f.v0 = crop(s.v0);
    return f;
}

PhysicsDef side_def(PhysicsDef d, Side nested_side) {
    (nested_side == Side::east ? d.east : d.west).kind = BoundaryKind::nested;
    return d;
}
}  // namespace

NestedSolver::NestedSolver(const Scene& scene, const PhysicsDef& def, const FiniteVolumeDef& fv, const NestDef& nest)
    : grid_(scene.grid),
      def_(def),
      rx_(nest.ratio),
      ry_(rows_ratio(scene.grid.ny, nest.ratio)),
      i_nest_(snapped_interface(scene, nest)),
      z_(scene.z),
      coarse_(coarse_scene(scene, rx_, ry_, i_nest_), side_def(def, Side::east), fv),
      fine_(fine_scene(scene, i_nest_), side_def(def, Side::west), fv) {
    const int rx = rx_, ry = ry_, ny = grid_.ny, ncy = ny / ry;
    // Ghost ground: the fine grid's west ghosts stand on the scene's own cells west of
    // the interface; the coarse grid's east ghosts on block averages east of it.
    std::vector<double> zf(std::size_t(kLayers * ny)), zc(std::size_t(kLayers * ncy));
    for (int L = 1; L <= kLayers; ++L) {
        for (int j = 0; j < ny; ++j) zf[std::size_t((L - 1) * ny + j)] = z_[grid_.index(i_nest_ - L, j)];
        for (int J = 0; J < ncy; ++J) {
            double sum = 0.0;
            for (int b = 0; b < ry; ++b)
                for (int a = 0; a < rx; ++a) sum += z_[grid_.index(i_nest_ + (L - 1) * rx + a, J * ry + b)];
            zc[std::size_t((L - 1) * ncy + J)] = sum / double(rx * ry);
        }
    }
    fine_.set_ghost_bed(Side::west, zf);
    coarse_.set_ghost_bed(Side::east, zc);
}

std::string NestedSolver::description() const {
    return coarse_.description() + "; nested: " + std::to_string(coarse_.grid().dx) +
           (ry_ == rx_ ? std::string() : " x " + std::to_string(coarse_.grid().dy)) +
           " m west of x = " + std::to_string(grid_.x_min_edge() + i_nest_ * grid_.dx) + " m, sub-cycled, refluxed";
}

void NestedSolver::set_time(double t) {
    time_ = t;
    coarse_.set_time(t);
    fine_.set_time(t);
}

SolverStats NestedSolver::stats() const {
    SolverStats s = coarse_.stats();
    s.negative_depth_fixes += fine_.stats().negative_depth_fixes;
    s.positivity_redos += fine_.stats().positivity_redos;
    s.min_depth_seen = std::min(s.min_depth_seen, fine_.stats().min_depth_seen);
    s.cell_stages += fine_.stats().cell_stages;
    s.cell_stages_dry += fine_.stats().cell_stages_dry;
    return s;
}

GhostState NestedSolver::coarse_ghosts_from_fine() const {
    const int rx = rx_, ry = ry_, ncy = grid_.ny / ry;
    GhostState g;
    for (auto* v : {&g.h, &g.hu, &g.hv}) v->assign(std::size_t(kLayers * ncy), 0.0);
    for (int L = 1; L <= kLayers; ++L)
        for (int J = 0; J < ncy; ++J) {
            double h = 0.0, hu = 0.0, hv = 0.0;
            for (int b = 0; b < ry; ++b)
                for (int a = 0; a < rx; ++a) {
                    const int i = (L - 1) * rx + a, j = J * ry + b;
                    h += fine_.depth(i, j);
                    hu += fine_.x_discharge(i, j);
                    hv += fine_.y_discharge(i, j);
                }
            const std::size_t q = std::size_t((L - 1) * ncy + J);
            const double inv = 1.0 / double(rx * ry);
            g.h[q] = h * inv;
            g.hu[q] = hu * inv;
            g.hv[q] = hv * inv;
        }
    return g;
}

GhostState NestedSolver::fine_ghosts_from_coarse() const {
    const Grid& cg = coarse_.grid();
    const int ny = grid_.ny, I = cg.nx - 1;  // the coarse column along the interface
    const double dry = def_.dry_depth;
    GhostState g;
    for (auto* v : {&g.h, &g.hu, &g.hv}) v->assign(std::size_t(kLayers * ny), 0.0);
    for (int j = 0; j < ny; ++j) {
        // Linear in y between the coarse row centres (held beyond the first and last);
        // from a single cell where a neighbour is dry.
        const double fy = std::clamp((grid_.y(j) - cg.y0) / cg.dy, 0.0, double(cg.ny - 1));
        const int J0 = std::min(int(fy), cg.ny - 2 < 0 ? 0 : cg.ny - 2);
        const int J1 = std::min(J0 + 1, cg.ny - 1);
        double w = fy - J0;
        if (coarse_.depth(I, J0) <= dry || coarse_.depth(I, J1) <= dry) w = w < 0.5 ? 0.0 : 1.0;
        const double eta = (1 - w) * coarse_.level(I, J0) + w * coarse_.level(I, J1);
        const double u = (1 - w) * coarse_.x_velocity(I, J0) + w * coarse_.x_velocity(I, J1);
        const double v = (1 - w) * coarse_.y_velocity(I, J0) + w * coarse_.y_velocity(I, J1);
        for (int L = 1; L <= kLayers; ++L) {
            const std::size_t q = std::size_t((L - 1) * ny + j);
            const double h = std::max(0.0, eta - z_[grid_.index(i_nest_ - L, j)]);
            g.h[q] = h;
            g.hu[q] = h > dry ? h * u : 0.0;
            g.hv[q] = h > dry ? h * v : 0.0;
        }
    }
    return g;
}

void NestedSolver::reflux() {
    const int ry = ry_, ncy = grid_.ny / ry, I = coarse_.grid().nx - 1;
    const std::vector<double>& tc = coarse_.side_transfer(Side::east);
    const std::vector<double>& tf = fine_.side_transfer(Side::west);
    const double dxc = coarse_.grid().dx;
    std::vector<double>& h = coarse_.depth_data();
    for (int J = 0; J < ncy; ++J) {
        double fine_sum = 0.0;  // the fine faces along coarse row J, per unit length of it
        for (int b = 0; b < ry; ++b) fine_sum += tf[std::size_t(J * ry + b)];
        fine_sum /= double(ry);
        double& hc = h[coarse_.at(I, J)];
        hc += (tc[std::size_t(J)] - fine_sum) / dxc;
        if (hc < 0.0) {
            hc = 0.0;
            ++reflux_clamps_;
        }
    }
}

double NestedSolver::stable_dt() const {
    const double coarse = coarse_.stable_dt(), fine = fine_.stable_dt();
    const double ratio = coarse / fine;
    if (!(ratio > 1.0)) return coarse;
    const double up = std::ceil(ratio - 1e-9), down = std::floor(ratio + 1e-9);
    // Cell-updates per simulated second: the coarse cells once per coarse step, the
    // fine cells once per sub-step.
    const double nc = double(coarse_.grid().size()), nf = double(fine_.grid().size());
    const double cost_coarse_step = (nc + up * nf) / coarse, cost_whole_fine = (nc + down * nf) / (down * fine);
    return cost_whole_fine < cost_coarse_step ? down * fine : coarse;
}

void NestedSolver::step(double dt) {
    const double t0 = time_, t1 = time_ + dt;
    const GhostState from_fine = coarse_ghosts_from_fine();
    coarse_.set_nested_ghosts(Side::east, t0, from_fine, t0, from_fine);
    const GhostState before = fine_ghosts_from_coarse();
    coarse_.reset_side_transfer();
    fine_.reset_side_transfer();

    coarse_.step(dt);
    cell_updates_ += double(coarse_.grid().size());
    fine_.set_nested_ghosts(Side::west, t0, before, t1, fine_ghosts_from_coarse());
    // Sub-steps: as few as the fine CFL allows, of equal length over what is left.
    while (fine_.time() < t1 - 1e-12 * std::max(1.0, t1)) {
        const double left = t1 - fine_.time();
        const double n = std::ceil(left / fine_.stable_dt() - 1e-9);
        const double dts = n <= 1.0 ? left : left / n;
        fine_.step(dts);
        ++fine_steps_;
        cell_updates_ += double(fine_.grid().size());
    }
    fine_.set_time(t1);
    coarse_.set_time(t1);
    reflux();
    time_ = t1;
}

double NestedSolver::depth(int i, int j) const {
    if (i >= i_nest_) return fine_.depth(i - i_nest_, j);
    const int I = i / rx_, J = j / ry_;
    if (coarse_.depth(I, J) <= def_.dry_depth) return 0.0;
    return std::max(0.0, coarse_.level(I, J) - z_[grid_.index(i, j)]);
}

void NestedSolver::state_row(int j, int i0, int i1, double* h, double* u, double* v) const {
    const int split = std::clamp(i_nest_, i0, i1);  // the range's first fine cell
    if (split < i1) fine_.state_row(j, split - i_nest_, i1 - i_nest_, h + (split - i0), u + (split - i0), v + (split - i0));
    // West of the interface: as depth() and x_velocity(), the coarse cell's level over
    // the scene's ground.
    const double dry = def_.dry_depth;
    const int J = j / ry_;
    for (int I = i0 / rx_; I * rx_ < split; ++I) {
        const double h_coarse = coarse_.depth(I, J);
        const bool coarse_wet = h_coarse > dry;
        const double level = coarse_.level(I, J), u_coarse = coarse_.x_velocity(I, J), v_coarse = coarse_.y_velocity(I, J);
        // A non-finite coarse state is passed on as it is, so the state checks name its cells.
        const bool finite = std::isfinite(h_coarse) && std::isfinite(u_coarse) && std::isfinite(v_coarse);
        for (int i = std::max(i0, I * rx_); i < std::min(split, (I + 1) * rx_); ++i) {
            const double d = !finite ? h_coarse : coarse_wet ? std::max(0.0, level - z_[grid_.index(i, j)]) : 0.0;
            const bool wet = !finite || d > dry;
            h[i - i0] = d;
            u[i - i0] = wet ? u_coarse : 0.0;
            v[i - i0] = wet ? v_coarse : 0.0;
        }
    }
}

double NestedSolver::x_velocity(int i, int j) const {
    if (i >= i_nest_) return fine_.x_velocity(i - i_nest_, j);
    return depth(i, j) > def_.dry_depth ? coarse_.x_velocity(i / rx_, j / ry_) : 0.0;
}

double NestedSolver::y_velocity(int i, int j) const {
    if (i >= i_nest_) return fine_.y_velocity(i - i_nest_, j);
    return depth(i, j) > def_.dry_depth ? coarse_.y_velocity(i / rx_, j / ry_) : 0.0;
}

}  // namespace flotsam::hydro
