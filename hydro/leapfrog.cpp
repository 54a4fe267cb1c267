#include "hydro/leapfrog.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.hpp"
#include "hydro/leapfrog_kernels.hpp"

namespace flotsam::hydro {

LeapfrogDef default_leapfrog_def() { return LeapfrogDef{}; }

namespace {
bool is_x_side(Side s) { return s == Side::west || s == Side::east; }
}  // namespace

std::size_t LeapfrogSolver::edge_cell(Side s, int k) const {
    if (is_x_side(s)) return at(s == Side::west ? 0 : grid_.nx - 1, k);
    return at(k, s == Side::south ? 0 : grid_.ny - 1);
}

namespace {

// The boundaries and settings the leap-frog is written for; the others name the option.
void check_leapfrog_options(const PhysicsDef& def, const LeapfrogDef& leapfrog) {
    for (const BoundaryDef* b : {&def.west, &def.east, &def.south, &def.north}) {
        if (b->kind == BoundaryKind::zero_gradient)
            fail("", "--scheme leapfrog",
                 "a zero-gradient side is a finite-volume study option (on a C-grid it would freeze the boundary "
                 "discharge): use transmissive");
        if (b->kind == BoundaryKind::forced)
            fail("", "--scheme leapfrog", "a side forced from a file is written for the finite-volume scheme: use --scheme fv");
        if (b->kind == BoundaryKind::nested)
            fail("", "--scheme leapfrog",
                 "nested grids (--nest-ratio > 1) are written for the finite-volume scheme: use --scheme fv with "
                 "--nest-ratio, or --nest-ratio 1 with --scheme leapfrog");
    }
    if (!(leapfrog.courant > 0.0)) fail("", "--courant", "must be positive");
    if (!def.study_past_stability_limit && leapfrog.courant > 1.0)
        fail("", "--courant", "must be at most 1 (the leap-frog's linear stability limit)");
    if (!(def.dry_depth > 0.0)) fail("", "--dry-depth", "must be positive");
}

}  // namespace

LeapfrogSolver::LeapfrogSolver(const Scene& scene, const PhysicsDef& def, const LeapfrogDef& leapfrog)
    : grid_(scene.grid),
      def_(def),
      lf_(leapfrog),
      forcing_({def.west, def.east, def.south, def.north}, def.pump, scene.grid, scene.z) {
    check_leapfrog_options(def, leapfrog);
    stride_ = std::size_t(grid_.nx + 2);
    const std::size_t n = stride_ * std::size_t(grid_.ny + 2);
    for (auto* v : {&h_, &u_, &v_, &m_, &n_, &u_new_, &v_new_, &m_new_, &n_new_, &z_, &g_n2_}) v->assign(n, 0.0);
    factor_.assign(n, 1.0);
    double deepest = initial_cells(scene);
    if (!scene.u0.empty()) initial_face_velocities(scene);
    deepest = record_rest_depths(deepest);
    dt_ = initial_step(scene, deepest);
}

double LeapfrogSolver::initial_cells(const Scene& scene) {
    const int nx = grid_.nx, ny = grid_.ny;
    double deepest = 0.0;
    for (int j = -1; j <= ny; ++j)
        for (int i = -1; i <= nx; ++i) {
            const int ic = std::clamp(i, 0, nx - 1), jc = std::clamp(j, 0, ny - 1);  // ghosts copy the edge
            const std::size_t k = grid_.index(ic, jc), p = at(i, j);
            z_[p] = scene.z[k];
            const double n_manning = scene.manning_n.empty() ? def_.default_manning_n : scene.manning_n[k];
            g_n2_[p] = def_.gravity * n_manning * n_manning;
            if (i != ic || j != jc) continue;
            const double eta0 = scene.eta0.empty() ? 0.0 : scene.eta0[k];
            h_[p] = std::max(0.0, eta0 - z_[p]);
            deepest = std::max(deepest, h_[p]);
        }
    return deepest;
}

void LeapfrogSolver::initial_face_velocities(const Scene& scene) {
    const int nx = grid_.nx, ny = grid_.ny;
    const double dry = def_.dry_depth;
    for (int j = 0; j < ny; ++j)
        for (int i = 1; i < nx; ++i) {
            const std::size_t p = at(i, j), q = p - 1;
            if (!face_open(h_[q], z_[q], h_[p], z_[p], dry)) continue;
            u_[p] = 0.5 * (scene.u0[grid_.index(i - 1, j)] + scene.u0[grid_.index(i, j)]);
            m_[p] = upstream_depth(u_[p], h_[q], z_[q], h_[p], z_[p], dry) * u_[p];
        }
    for (int j = 1; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const std::size_t p = at(i, j), q = p - stride_;
            if (!face_open(h_[q], z_[q], h_[p], z_[p], dry)) continue;
            v_[p] = 0.5 * (scene.v0[grid_.index(i, j - 1)] + scene.v0[grid_.index(i, j)]);
            n_[p] = upstream_depth(v_[p], h_[q], z_[q], h_[p], z_[p], dry) * v_[p];
        }
}

double LeapfrogSolver::record_rest_depths(double deepest) {
    for (Side s : {Side::west, Side::east, Side::south, Side::north})
        for (int k = 0; k < (is_x_side(s) ? grid_.ny : grid_.nx); ++k) {
            const std::size_t e = edge_cell(s, k);
            rest_depth_[int(s)].push_back(h_[e]);
            if (forcing_.def(s).kind == BoundaryKind::level) deepest = std::max(deepest, -z_[e] + forcing_.series_max(s));
        }
    return deepest;
}

// The largest Courant rate at the start: the deepest water at rest, and every cell of a
// scene that starts moving with its |u| + c per direction (courant_number).
double LeapfrogSolver::initial_step(const Scene& scene, double deepest) const {
    const double wave_metric = std::sqrt(1.0 / (grid_.dx * grid_.dx) + 1.0 / (grid_.dy * grid_.dy));
    double rate = std::sqrt(def_.gravity * deepest) * wave_metric;
    if (!scene.u0.empty())
        for (int j = 0; j < grid_.ny; ++j)
            for (int i = 0; i < grid_.nx; ++i) {
                const std::size_t k = grid_.index(i, j);
                if (h_[at(i, j)] > def_.dry_depth)
                    rate = std::max(rate, courant_number(h_[at(i, j)], scene.u0[k], scene.v0[k], def_.gravity, 1.0, 1.0 / grid_.dx,
                                                         1.0 / grid_.dy));
            }
    double dt = def_.max_dt;
    if (rate > 0.0) dt = std::min(dt, lf_.courant / rate);
    if (lf_.step_divides > 0.0) dt = lf_.step_divides / std::ceil(lf_.step_divides / dt - 1e-9);
    return dt;
}

std::string LeapfrogSolver::description() const {
    return "staggered C-grid, leap-frog, first-order upwind momentum advection, semi-implicit Manning, outflow limiter; fixed "
           "step " +
           std::to_string(stable_dt()) + " s (Courant " + std::to_string(lf_.courant) + ")";
}

double LeapfrogSolver::volume() const {
    double v = 0.0;  // serial: the same sum whatever the thread count
    for (int j = 0; j < grid_.ny; ++j)
        for (int i = 0; i < grid_.nx; ++i) v += h_[at(i, j)];
    return v * grid_.dx * grid_.dy;
}

// Boundary faces' new velocities and discharges (into u_new_ ... n_new_) and the ghost
// cells' depths, from the state at t.
void LeapfrogSolver::boundary_faces(double t) {
    const double g = def_.gravity, dry = def_.dry_depth;
    const int nx = grid_.nx, ny = grid_.ny;
    for (Side s : {Side::west, Side::east, Side::south, Side::north}) {
        const SideForcing f = forcing_.at(s, t, [&] {
            double sum = 0.0;
            for (auto [i, j] : forcing_.pump_cells()) sum += level(i, j);
            return sum / double(forcing_.pump_cells().size());
        });
        const bool xs = is_x_side(s);
        // Inward normal: +x at the west, -x at the east, +y at the south, -y at the north.
        const bool low_side = s == Side::west || s == Side::south;
        const double sign = low_side ? 1.0 : -1.0;
        std::vector<double>& vel_new = xs ? u_new_ : v_new_;
        std::vector<double>& q_new = xs ? m_new_ : n_new_;
        const std::vector<double>& vel = xs ? u_ : v_;
        const int n_along = xs ? ny : nx;
        // Neighbours along the inward normal: ghost - edge, faces at the side and inside.
        const std::ptrdiff_t inward =
            xs ? (s == Side::west ? 1 : -1) : (s == Side::south ? std::ptrdiff_t(stride_) : -std::ptrdiff_t(stride_));
        for (int k = 0; k < n_along; ++k) {
            const std::size_t edge = edge_cell(s, k);
            const std::size_t ghost = edge - inward;
            const std::size_t face = low_side ? edge : ghost;  // a face is stored at the cell on its +x (+y) side
            const std::size_t inner_face = low_side ? edge + inward : edge;
            if (f.kind == BoundaryKind::wall) {
                h_[ghost] = h_[edge];
                vel_new[face] = q_new[face] = 0.0;
                continue;
            }
            const double h_in = h_[edge];
            const double un_in = h_in > dry ? sign * 0.5 * (vel[face] + vel[inner_face]) : 0.0;
            const double h0 = f.kind == BoundaryKind::transmissive ? rest_depth_[int(s)][std::size_t(k)] : std::max(0.0, -z_[edge]);
            double hb = 0.0, unb = 0.0;
            open_side_state(f, h_in, un_in, h0, g, dry, hb, unb);
            h_[ghost] = hb;
            vel_new[face] = hb > dry ? sign * unb : 0.0;
            q_new[face] = sign * hb * unb;
        }
    }
}

// New velocities and discharges of the interior faces, from h^n, u, v at t^(n-1/2) and
// the previous step's discharges.
void LeapfrogSolver::momentum(double dt) {
    const int nx = grid_.nx, ny = grid_.ny;
    const double g = def_.gravity, dry = def_.dry_depth, dx = grid_.dx, dy = grid_.dy, idx = 1.0 / dx, idy = 1.0 / dy;
    const std::size_t s = stride_;
    // Tangential velocities beyond the sides copy the edge (zero gradient; a slip wall).
    for (int i = 0; i <= nx; ++i) {
        u_[at(i, -1)] = u_[at(i, 0)];
        u_[at(i, ny)] = u_[at(i, ny - 1)];
    }
    for (int j = 0; j <= ny; ++j) {
        v_[at(-1, j)] = v_[at(0, j)];
        v_[at(nx, j)] = v_[at(nx - 1, j)];
    }
    const double* __restrict h = h_.data();
    const double* __restrict z = z_.data();
    const double* __restrict u = u_.data();
    const double* __restrict v = v_.data();
    const double* __restrict m = m_.data();
    const double* __restrict n = n_.data();
    const double* __restrict gn2 = g_n2_.data();
    double* __restrict u_new = u_new_.data();
    double* __restrict v_new = v_new_.data();
    double* __restrict m_new = m_new_.data();
    double* __restrict n_new = n_new_.data();
#pragma omp parallel for schedule(static)
    for (int j = 0; j <= ny; ++j) {
        const std::size_t p0 = at(0, j);
        if (j < ny) {
#pragma omp simd
            for (int i = 1; i < nx; ++i) {  // interior x-faces: cells L = p - 1, R = p
                const std::size_t p = p0 + std::size_t(i), l = p - 1;
                const double inflow =
                    momentum_inflow(0.5 * (m[l] + m[p]), u[l], 0.5 * (m[p] + m[p + 1]), u[p + 1], u[p]) * idx +
                    momentum_inflow(0.5 * (n[l] + n[p]), u[p - s], 0.5 * (n[l + s] + n[p + s]), u[p + s], u[p]) * idy;
                const double v_mean = 0.25 * (v[l] + v[p] + v[l + s] + v[p + s]);
                u_new[p] =
                    face_step(u[p], v_mean, h[l], z[l], h[p], z[p], 0.5 * (gn2[l] + gn2[p]), dx, inflow, g, dt, dry, m_new[p]);
            }
        }
        if (j == 0 || j == ny) continue;
#pragma omp simd
        for (int i = 0; i < nx; ++i) {  // interior y-faces: cells S = p - s, N = p
            const std::size_t p = p0 + std::size_t(i), b = p - s;
            const double inflow = momentum_inflow(0.5 * (n[b] + n[p]), v[b], 0.5 * (n[p] + n[p + s]), v[p + s], v[p]) * idy +
                                  momentum_inflow(0.5 * (m[b] + m[p]), v[p - 1], 0.5 * (m[b + 1] + m[p + 1]), v[p + 1], v[p]) * idx;
            const double u_mean = 0.25 * (u[b] + u[p] + u[b + 1] + u[p + 1]);
            v_new[p] = face_step(v[p], u_mean, h[b], z[b], h[p], z[p], 0.5 * (gn2[b] + gn2[p]), dy, inflow, g, dt, dry, n_new[p]);
        }
    }
}

void LeapfrogSolver::limit_outflow(double dt) {
    const int nx = grid_.nx, ny = grid_.ny;
    const double rx = dt / grid_.dx, ry = dt / grid_.dy;
    const std::size_t s = stride_;
    long limited = 0;
#pragma omp parallel for reduction(+ : limited) schedule(static)
    for (int j = 0; j < ny; ++j) {
        const std::size_t p0 = at(0, j);
#pragma omp simd reduction(+ : limited)
        for (int i = 0; i < nx; ++i) {
            const std::size_t p = p0 + std::size_t(i);
            const double out = rx * (std::max(0.0, m_new_[p + 1]) - std::min(0.0, m_new_[p])) +
                               ry * (std::max(0.0, n_new_[p + s]) - std::min(0.0, n_new_[p]));
            const double f = outflow_factor(h_[p], out);
            factor_[p] = f;
            limited += f < 1.0 ? 1 : 0;
        }
    }
    if (limited > 0) {
#pragma omp parallel for schedule(static)
        for (int j = 0; j <= ny; ++j) {
            const std::size_t p0 = at(0, j);
            if (j < ny)
                for (int i = 0; i <= nx; ++i) {
                    const std::size_t p = p0 + std::size_t(i);
                    const double f = upstream_factor(m_new_[p], factor_[p - 1], factor_[p]);
                    m_new_[p] *= f;
                    u_new_[p] *= f;
                }
            for (int i = 0; i < nx; ++i) {
                const std::size_t p = p0 + std::size_t(i);
                const double f = upstream_factor(n_new_[p], factor_[p - s], factor_[p]);
                n_new_[p] *= f;
                v_new_[p] *= f;
            }
        }
    }
    stats_.outflow_limits += limited;
}

void LeapfrogSolver::continuity(double dt) {
    const int nx = grid_.nx, ny = grid_.ny;
    const double rx = dt / grid_.dx, ry = dt / grid_.dy, g = def_.gravity, dry = def_.dry_depth;
    const double idx = 1.0 / grid_.dx, idy = 1.0 / grid_.dy;
    const std::size_t s = stride_;
    auto cell_courant = [&](std::size_t p) {
        const double wet = h_[p] > dry ? 0.5 : 0.0;
        return courant_number(h_[p], wet * (u_new_[p] + u_new_[p + 1]), wet * (v_new_[p] + v_new_[p + s]), g, dt_, idx, idy);
    };
    long fixes = 0;
    double worst = 0.0, courant = 0.0;
#pragma omp parallel for reduction(+ : fixes) reduction(min : worst) reduction(max : courant) schedule(static)
    for (int j = 0; j < ny; ++j) {
        const std::size_t p0 = at(0, j);
#pragma omp simd reduction(+ : fixes) reduction(min : worst) reduction(max : courant)
        for (int i = 0; i < nx; ++i) {
            const std::size_t p = p0 + std::size_t(i);
            double h = h_[p] - rx * (m_new_[p + 1] - m_new_[p]) - ry * (n_new_[p + s] - n_new_[p]);
            if (h < 0.0) {  // only round-off after the outflow limiter; counted, then removed
                worst = std::min(worst, h);
                ++fixes;
                h = 0.0;
            }
            h_[p] = h;
            courant = std::max(courant, cell_courant(p));
        }
    }
    stats_.negative_depth_fixes += fixes;
    stats_.min_depth_seen = std::min(stats_.min_depth_seen, worst);
    max_courant_ = std::max(max_courant_, courant);
    if (!def_.study_past_stability_limit && courant > 1.0) {
        int wi = 0, wj = 0;
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i)
                if (cell_courant(at(i, j)) >= courant) wi = i, wj = j;
        fail("", "--courant",
             "the leap-frog step of " + std::to_string(dt_) + " s reached Courant number " + std::to_string(courant) +
                 " > 1 at t = " + std::to_string(time_ + dt) + " s, x = " + std::to_string(grid_.x(wi)) +
                 " m, y = " + std::to_string(grid_.y(wj)) + " m (depth " + std::to_string(depth(wi, wj)) +
                 " m): the water got deeper or faster than the step was chosen for; "
                 "lower --courant");
    }
}

void LeapfrogSolver::step(double dt) {
    boundary_faces(time_);
    momentum(dt);
    limit_outflow(dt);
    continuity(dt);
    const double rate = forcing_.pump_rate(time_);  // [m/s] over the pump's strip
    if (rate > 0.0)
        for (auto [i, j] : forcing_.pump_cells()) h_[at(i, j)] += dt * rate;
    std::swap(u_, u_new_);
    std::swap(v_, v_new_);
    std::swap(m_, m_new_);
    std::swap(n_, n_new_);
    time_ += dt;
    ++stats_.steps;
}

}  // namespace flotsam::hydro
