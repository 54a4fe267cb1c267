#include "hydro/nesting.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "common/error.hpp"

namespace flotsam::hydro {

NestDef default_nest_def() { return NestDef{}; }

bool NestDef::nested() const {
    return std::any_of(ratio.begin(), ratio.end(), [](int r) { return r > 1; });
}

int rows_ratio(int rows, int ratio) {
    int r = std::min(ratio, rows);
    while (rows % r != 0) --r;
    return r;
}

namespace {
constexpr int kLayers = kGhost;  // ghost layers of hydro::Solver (column_range.hpp)

// Each slab's ratio and first scene column (and the scene's nx after the last), from the
// interfaces. An interface west of the finest slab is moved west to a whole number of the
// coarser neighbour's cells from the scene's west edge; one east of it, east to a whole
// number from the east edge.
struct Layout {
    std::vector<int> ratio, start;
};

Layout slab_layout(const Scene& s, const NestDef& n) {
    Layout l;
    l.ratio = n.ratio;
    if (l.ratio.size() == n.x.size()) l.ratio.push_back(1);
    if (l.ratio.size() != n.x.size() + 1)
        fail(s.path, "--nest-ratio", "give one ratio per grid: as many as --nest-x interfaces, or one more");
    if (!n.nested()) fail(s.path, "--nest-ratio", "must be 2 or more for a nested run");
    for (int r : l.ratio)
        if (r < 1) fail(s.path, "--nest-ratio", "ratios must be 1 or more");
    const int finest = int(std::min_element(l.ratio.begin(), l.ratio.end()) - l.ratio.begin());
    const int finest_ratio = l.ratio[std::size_t(finest)];
    for (std::size_t k = 0; k + 1 < l.ratio.size(); ++k) {
        const int a = l.ratio[k], b = l.ratio[k + 1], hi = std::max(a, b), lo = std::min(a, b);
        if (a == b) {
            // Two slabs of the finest spacing side by side: a time interface, each with a
            // step of its own.
            if (a != finest_ratio)
                fail(s.path, "--nest-ratio",
                     "neighbouring grids of the same ratio (a time interface) must be of the finest ratio, " +
                         std::to_string(finest_ratio));
            continue;
        }
        if (hi % lo != 0) fail(s.path, "--nest-ratio", "neighbouring grids need ratios the larger of which is a multiple of the smaller");
        if ((int(k) < finest) != (a > b))
            fail(s.path, "--nest-ratio", "ratios must fall from the west to the finest grid and rise after it");
    }
    l.start.push_back(0);
    for (std::size_t k = 0; k < n.x.size(); ++k) {
        const int i = int(std::floor((n.x[k] - s.grid.x_min_edge()) / s.grid.dx + 1e-9));
        const int r = std::max(l.ratio[k], l.ratio[k + 1]);
        const int snapped = l.ratio[k] > l.ratio[k + 1] ? (i / r) * r : s.grid.nx - ((s.grid.nx - i) / r) * r;
        l.start.push_back(snapped);
    }
    l.start.push_back(s.grid.nx);
    for (std::size_t k = 0; k < l.ratio.size(); ++k) {
        int need = 2 * l.ratio[k];  // two of its own cells, and two of a coarser neighbour's
        if (k > 0) need = std::max(need, 2 * l.ratio[k - 1]);
        if (k + 1 < l.ratio.size()) need = std::max(need, 2 * l.ratio[k + 1]);
        if (l.start[k + 1] - l.start[k] < need)
            fail(s.path, "--nest-x",
                 "the interfaces must leave each grid at least 2 of its own cells and 2 of a coarser neighbour's (grid " +
                     std::to_string(k + 1) + " has " + std::to_string(l.start[k + 1] - l.start[k]) + " scene columns, needs " +
                     std::to_string(need) + ")");
    }
    return l;
}

// The scene's columns [i0, i1) in blocks of rx x ry cells (cell for cell where both are 1).
Scene slab_scene(const Scene& s, int i0, int i1, int rx, int ry) {
    Scene c;
    c.path = s.path;
    c.grid = s.grid;
    c.grid.nx = (i1 - i0) / rx;
    c.grid.ny = s.grid.ny / ry;
    c.grid.dx = s.grid.dx * rx;
    c.grid.dy = s.grid.dy * ry;
    c.grid.x0 = s.grid.x(i0) + 0.5 * (rx - 1) * s.grid.dx;
    c.grid.y0 = s.grid.y0 + 0.5 * (ry - 1) * s.grid.dy;
    auto block = [&](const auto& f) {
        std::remove_cvref_t<decltype(f)> out;
        if (f.empty()) return out;
        out.reserve(c.grid.size());
        for (int J = 0; J < c.grid.ny; ++J)
            for (int I = 0; I < c.grid.nx; ++I) {
                if (rx * ry == 1) {
                    out.push_back(f[s.grid.index(i0 + I, J)]);
                    continue;
                }
                double sum = 0.0;
                for (int b = 0; b < ry; ++b)
                    for (int a = 0; a < rx; ++a) sum += f[s.grid.index(i0 + I * rx + a, J * ry + b)];
                out.push_back(sum / double(rx * ry));
            }
        return out;
    };
    c.z = block(s.z);
    c.manning_n = block(s.manning_n);
    c.eta0 = block(s.eta0);
    c.u0 = block(s.u0);
    c.v0 = block(s.v0);
    if (rx * ry == 1) c.building = block(s.building);
    return c;
}

PhysicsDef slab_def(PhysicsDef d, bool west_nested, bool east_nested) {
    if (west_nested) d.west.kind = BoundaryKind::nested;
    if (east_nested) d.east.kind = BoundaryKind::nested;
    return d;
}

// Ground of a slab's ghost cells beyond its side (west: columns before i0, east: from i1),
// layer by layer (GhostState's layout): the scene's cells there in the slab's blocks.
std::vector<double> ghost_bed(const Scene& s, int i0, int i1, int rx, int ry, Side side) {
    const int ny = s.grid.ny / ry;
    std::vector<double> z(std::size_t(kLayers * ny));
    for (int L = 1; L <= kLayers; ++L)
        for (int J = 0; J < ny; ++J) {
            const int first = side == Side::west ? i0 - L * rx : i1 + (L - 1) * rx;
            double& out = z[std::size_t((L - 1) * ny + J)];
            if (rx * ry == 1) {
                out = s.z[s.grid.index(first, J)];
                continue;
            }
            double sum = 0.0;
            for (int b = 0; b < ry; ++b)
                for (int a = 0; a < rx; ++a) sum += s.z[s.grid.index(first + a, J * ry + b)];
            out = sum / double(rx * ry);
        }
    return z;
}

}  // namespace

template <class Real>
BasicNestedSolver<Real>::BasicNestedSolver(const Scene& scene, const PhysicsDef& def, const FiniteVolumeDef& fv, const NestDef& nest)
    : grid_(scene.grid), def_(def), z_(scene.z) {
    const Layout l = slab_layout(scene, nest);
    const std::size_t n = l.ratio.size();
    slabs_.reserve(n);
    for (std::size_t k = 0; k < n; ++k) {
        const int rx = l.ratio[k], ry = rows_ratio(scene.grid.ny, rx), i0 = l.start[k], i1 = l.start[k + 1];
        slabs_.push_back(Slab{i0, i1, rx, ry, SlabSolver(slab_scene(scene, i0, i1, rx, ry), slab_def(def, k > 0, k + 1 < n), fv)});
        if (k > 0) slabs_.back().solver.set_ghost_bed(Side::west, ghost_bed(scene, i0, i1, rx, ry, Side::west));
        if (k + 1 < n) slabs_.back().solver.set_ghost_bed(Side::east, ghost_bed(scene, i0, i1, rx, ry, Side::east));
    }
    for (std::size_t k = 0; k + 1 < n; ++k) {
        Interface f;
        f.west = int(k);
        f.same_grid = slabs_[k].rx == slabs_[k + 1].rx;
        f.coarse_west = slabs_[k].rx > slabs_[k + 1].rx;
        const Slab &c = slabs_[std::size_t(f.coarse())], &fn = slabs_[std::size_t(f.fine())];
        f.rx = c.rx / fn.rx;
        if (c.ry % fn.ry != 0)
            fail(scene.path, "--nest-ratio",
                 "the grids' cells along y do not nest (" + std::to_string(scene.grid.ny) + " rows): choose ratios that divide them");
        f.ry = c.ry / fn.ry;
        f.fine_bed = ghost_bed(scene, fn.i0, fn.i1, fn.rx, fn.ry, f.fine_side());
        f.coarse_bed = ghost_bed(scene, c.i0, c.i1, c.rx, c.ry, f.coarse_side());
        interfaces_.push_back(std::move(f));
    }
    order_.resize(n);
    std::iota(order_.begin(), order_.end(), 0);
    std::stable_sort(order_.begin(), order_.end(), [&](int a, int b) { return slabs_[std::size_t(a)].rx > slabs_[std::size_t(b)].rx; });
    volume_start_ = volume();
    time_interfaces_ = std::any_of(interfaces_.begin(), interfaces_.end(), [](const Interface& f) { return f.same_grid; });
    coarsest_ = slabs_[std::size_t(order_.front())].rx;
    finest_ = slabs_[std::size_t(order_.back())].rx;
}

template <class Real>
std::string BasicNestedSolver<Real>::description() const {
    std::string slabs;
    for (const Slab& b : slabs_) {
        if (b.rx == finest_) continue;
        const Grid& g = b.solver.grid();
        const double x0 = grid_.x_min_edge() + b.i0 * grid_.dx, x1 = grid_.x_min_edge() + b.i1 * grid_.dx;
        slabs += (slabs.empty() ? "" : ", ") + std::to_string(g.dx) + (b.ry == b.rx ? std::string() : " x " + std::to_string(g.dy)) +
                 " m" +
                 (b.i0 == 0             ? " west of x = " + std::to_string(x1)
                  : b.i1 == grid_.nx ? " east of x = " + std::to_string(x0)
                                         : " from x = " + std::to_string(x0) + " to " + std::to_string(x1)) +
                 " m";
    }
    std::string split;  // time interfaces: where the finest grid's parts meet
    for (const Interface& f : interfaces_)
        if (f.same_grid) split += (split.empty() ? "" : ", ") + std::to_string(grid_.x_min_edge() + slabs_[std::size_t(f.west + 1)].i0 * grid_.dx);
    if (!split.empty()) split = "; the finest grid in parts with steps of their own, split at x = " + split + " m";
    return slabs_.front().solver.description() + "; nested: " + slabs + ", sub-cycled, refluxed" + split;
}

template <class Real>
void BasicNestedSolver<Real>::set_time(double t) {
    time_ = t;
    for (Slab& b : slabs_) b.solver.set_time(t);
}

template <class Real>
SolverStats BasicNestedSolver<Real>::stats() const {
    SolverStats s = slabs_.front().solver.stats();
    for (std::size_t k = 1; k < slabs_.size(); ++k) {
        const SolverStats& f = slabs_[k].solver.stats();
        s.negative_depth_fixes += f.negative_depth_fixes;
        s.positivity_redos += f.positivity_redos;
        s.min_depth_seen = std::min(s.min_depth_seen, f.min_depth_seen);
        s.cell_stages += f.cell_stages;
        s.cell_stages_dry += f.cell_stages_dry;
    }
    // An interface cell refluxed below zero and set to 0 made water: said as a clamp.
    s.negative_depth_fixes += reflux_clamps_;
    return s;
}

template <class Real>
double BasicNestedSolver<Real>::volume() const {
    double v = 0.0;
    for (const Slab& b : slabs_) v += b.solver.volume();
    return v;
}

template <class Real>
std::vector<StateArray> BasicNestedSolver<Real>::state_arrays() {
    std::vector<StateArray> a;
    for (Slab& b : slabs_)
        for (const StateArray& v : b.solver.state_arrays()) a.push_back(v);
    return a;
}

template <class Real>
double BasicNestedSolver<Real>::stable_dt() const {
    // The coarsest slabs take one step; each other slab k ceil(dt / limit_k) sub-steps.
    double coarse = slabs_[std::size_t(order_.front())].solver.stable_dt();
    std::vector<double> limit(slabs_.size());
    for (std::size_t k = 0; k < slabs_.size(); ++k) {
        limit[k] = slabs_[k].solver.stable_dt();
        if (slabs_[k].rx == coarsest_) coarse = std::min(coarse, limit[k]);
    }
    // Cell-updates per simulated second, the slabs in stepping order.
    auto cost = [&](double dt) {
        double updates = 0.0;
        for (int k : order_) {
            const Slab& b = slabs_[std::size_t(k)];
            const double steps = b.rx == coarsest_ ? 1.0 : std::ceil(dt / limit[std::size_t(k)] - 1e-9);
            updates += steps * double(b.solver.grid().size());
        }
        return updates / dt;
    };
    // The coarse step, or a whole number of a finer slab's steps at its limit.
    double best = coarse, best_cost = -1.0;
    for (int k : order_) {
        const double ratio = coarse / limit[std::size_t(k)];
        if (slabs_[std::size_t(k)].rx == coarsest_ || !(ratio > 1.0)) continue;
        if (best_cost < 0.0) best_cost = cost(coarse);
        const double down = std::floor(ratio + 1e-9), dt = down * limit[std::size_t(k)];
        const double c = cost(dt);
        if (c < best_cost) {
            best = dt;
            best_cost = c;
        }
    }
    return best;
}

template <class Real>
void BasicNestedSolver<Real>::step(double dt) {
    const double t0 = time_, t1 = time_ + dt;
    if (time_interfaces_) order_for_step(dt);
    for (Interface& f : interfaces_) {
        const GhostState from_fine = coarse_ghosts_from_fine(f);
        slabs_[std::size_t(f.coarse())].solver.set_nested_ghosts(f.coarse_side(), t0, from_fine, t0, from_fine);
        f.before = fine_ghosts_from_coarse(f);
    }
    for (Slab& b : slabs_) b.solver.reset_side_transfer();
    for (int k : order_) {
        Slab& b = slabs_[std::size_t(k)];
        // Its ghosts from coarser neighbours, which have stepped: linear in time over the step.
        for (const Interface& f : interfaces_)
            if (f.fine() == k) b.solver.set_nested_ghosts(f.fine_side(), t0, f.before, t1, fine_ghosts_from_coarse(f));
        if (b.rx == coarsest_) {
            b.solver.step(dt);
            cell_updates_ += double(b.solver.grid().size());
            continue;
        }
        // Sub-steps: as few as the slab's CFL allows, of equal length over what is left.
        while (b.solver.time() < t1 - 1e-12 * std::max(1.0, t1)) {
            const double left = t1 - b.solver.time();
            const double n = std::ceil(left / b.solver.stable_dt() - 1e-9);
            const double dts = n <= 1.0 ? left : left / n;
            b.solver.step(dts);
            if (b.rx == finest_) ++fine_steps_;
            cell_updates_ += double(b.solver.grid().size());
        }
    }
    for (Slab& b : slabs_) b.solver.set_time(t1);
    for (const Interface& f : interfaces_) reflux(f);
    time_ = t1;
    // The fine side drew more water through an interface than the coarse cell beside it
    // had: where the two grids see different ground (a shore, a building averaged into a
    // coarse cell). Clamping it made water; past a millionth of the volume that is an
    // interface in the wrong place, not round-off.
    if (reflux_made_ > 1e-6 * volume_start_) {
        char what[200];
        std::snprintf(what, sizeof what, "%.3g m^3 of water made by t = %.3f s", reflux_made_, t1);
        fail("", "--nest-x",
             std::string("an interface crosses ground that wets and dries (the grids on its two sides see different "
                         "shores): refluxing drew more water than a coarse cell held, ") +
                 what + "; move it into water that stays wet (docs/accuracy.md, \"Nested grids\")");
    }
}

template <class Real>
void BasicNestedSolver<Real>::order_for_step(double dt) {
    // Slabs of the same spacing step in the order of their sub-steps this step, fewest
    // first (west first among equals), and the first of a time interface's two is its
    // coarse side: its ghosts hold the other's cells at the step's start, the other's
    // follow it in time and its faces' transfer is refluxed.
    std::vector<double> substeps(slabs_.size(), 1.0);
    for (std::size_t k = 0; k < slabs_.size(); ++k)
        if (slabs_[k].rx != coarsest_) substeps[k] = std::ceil(dt / slabs_[k].solver.stable_dt() - 1e-9);
    std::iota(order_.begin(), order_.end(), 0);
    std::stable_sort(order_.begin(), order_.end(), [&](int a, int b) {
        const Slab &sa = slabs_[std::size_t(a)], &sb = slabs_[std::size_t(b)];
        if (sa.rx != sb.rx) return sa.rx > sb.rx;
        return substeps[std::size_t(a)] < substeps[std::size_t(b)];
    });
    std::vector<int> position(slabs_.size());
    for (std::size_t p = 0; p < order_.size(); ++p) position[std::size_t(order_[p])] = int(p);
    for (Interface& f : interfaces_)
        if (f.same_grid) f.coarse_west = position[std::size_t(f.west)] < position[std::size_t(f.west + 1)];
}

template <class Real>
ColumnRange BasicNestedSolver<Real>::wet_columns(int j) const {
    ColumnRange c;
    for (const Slab& b : slabs_) {
        const ColumnRange s = b.solver.wet_columns(j / b.ry);
        if (!s.empty()) c = hull(c, {b.i0 + s.begin * b.rx, b.i0 + s.end * b.rx});
    }
    return c;
}

template <class Real>
const typename BasicNestedSolver<Real>::Slab& BasicNestedSolver<Real>::slab_of(int i) const {
    for (const Slab& b : slabs_)
        if (i < b.i1) return b;
    return slabs_.back();
}

template <class Real>
double BasicNestedSolver<Real>::depth(int i, int j) const {
    const Slab& b = slab_of(i);
    if (b.rx * b.ry == 1) return b.solver.depth(i - b.i0, j);
    const int I = (i - b.i0) / b.rx, J = j / b.ry;
    if (b.solver.depth(I, J) <= def_.dry_depth) return 0.0;
    return std::max(0.0, b.solver.level(I, J) - z_[grid_.index(i, j)]);
}

template <class Real>
void BasicNestedSolver<Real>::state_row(int j, int i0, int i1, double* h, double* u, double* v) const {
    const double dry = def_.dry_depth;
    for (const Slab& b : slabs_) {
        const int lo = std::max(i0, b.i0), hi = std::min(i1, b.i1);
        if (lo >= hi) continue;
        if (b.rx * b.ry == 1) {
            b.solver.state_row(j, lo - b.i0, hi - b.i0, h + (lo - i0), u + (lo - i0), v + (lo - i0));
            continue;
        }
        // A coarse slab: as depth() and x_velocity(), the coarse cell's level over the
        // scene's ground.
        const int J = j / b.ry;
        for (int I = (lo - b.i0) / b.rx; b.i0 + I * b.rx < hi; ++I) {
            const double h_coarse = b.solver.depth(I, J);
            const bool coarse_wet = h_coarse > dry;
            const double level = b.solver.level(I, J), u_coarse = b.solver.x_velocity(I, J), v_coarse = b.solver.y_velocity(I, J);
            // A non-finite coarse state is passed on as it is, so the state checks name its cells.
            const bool finite = std::isfinite(h_coarse) && std::isfinite(u_coarse) && std::isfinite(v_coarse);
            for (int i = std::max(lo, b.i0 + I * b.rx); i < std::min(hi, b.i0 + (I + 1) * b.rx); ++i) {
                const double d = !finite ? h_coarse : coarse_wet ? std::max(0.0, level - z_[grid_.index(i, j)]) : 0.0;
                const bool wet = !finite || d > dry;
                h[i - i0] = d;
                u[i - i0] = wet ? u_coarse : 0.0;
                v[i - i0] = wet ? v_coarse : 0.0;
            }
        }
    }
}

template <class Real>
double BasicNestedSolver<Real>::x_velocity(int i, int j) const {
    const Slab& b = slab_of(i);
    if (b.rx * b.ry == 1) return b.solver.x_velocity(i - b.i0, j);
    return depth(i, j) > def_.dry_depth ? b.solver.x_velocity((i - b.i0) / b.rx, j / b.ry) : 0.0;
}

template <class Real>
double BasicNestedSolver<Real>::y_velocity(int i, int j) const {
    const Slab& b = slab_of(i);
    if (b.rx * b.ry == 1) return b.solver.y_velocity(i - b.i0, j);
    return depth(i, j) > def_.dry_depth ? b.solver.y_velocity((i - b.i0) / b.rx, j / b.ry) : 0.0;
}

template class BasicNestedSolver<double>;
template class BasicNestedSolver<float>;

}  // namespace flotsam::hydro
