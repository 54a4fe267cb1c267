#include "hydro/solver.hpp"

#include <omp.h>
#include <xmmintrin.h>

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "hydro/swe_kernels.hpp"

namespace flotsam::hydro {

Friction parse_friction(const std::string& s, const std::string& option) {
    if (s == "implicit") return Friction::implicit;
    if (s == "explicit") return Friction::explicit_;
    fail("", option, "unknown friction treatment '" + s + "' (implicit, explicit)");
}

SolverDef default_solver_def() {
    SolverDef d;
    d.west.kind = BoundaryKind::level;
    d.east.kind = BoundaryKind::transmissive;
    d.south.kind = BoundaryKind::wall;
    d.north.kind = BoundaryKind::wall;
    return d;
}

namespace {
constexpr int kGhost = 2;

// Flush subnormal numbers to zero on this thread. Friction shrinks discharges in thin
// films geometrically, into the subnormal range, where every operation costs ~100
// cycles; values below 1e-308 carry no physics.
inline void flush_subnormals() { _mm_setcsr(_mm_getcsr() | 0x8040); }
bool is_x_side(Side s) { return s == Side::west || s == Side::east; }
}  // namespace

Solver::Solver(const Scene& scene, const SolverDef& def)
    : grid_(scene.grid), def_(def), forcing_({def.west, def.east, def.south, def.north}, scene.grid, scene.z) {
    if (def.order != 1 && def.order != 2) fail("", "--order", "must be 1 or 2");
    if (!(def.cfl > 0.0 && (def.cfl <= 0.5 || def.study_past_stability_limit)))
        fail("", "--cfl", "must be in (0, 0.5] (positivity of the depth needs <= 0.5)");
    if (!(def.dry_depth > 0.0)) fail("", "--dry-depth", "must be positive");
    stride_ = std::size_t(grid_.nx + 2 * kGhost);
    rows_ = std::size_t(grid_.ny + 2 * kGhost);
    const std::size_t n = stride_ * rows_;
    for (auto* v : {&h_, &hu_, &hv_, &h1_, &hu1_, &hv1_, &dh_, &dhu_, &dhv_, &eta_, &u_, &v_, &sy_eta_, &sy_h_, &sy_u_, &sy_v_, &gy_mass_,
                    &gy_lo_, &gy_hi_, &gy_tan_, &z_, &g_n2_})
        v->assign(n, 0.0);

    for (int j = 0; j < grid_.ny; ++j)
        for (int i = 0; i < grid_.nx; ++i) {
            const std::size_t k = grid_.index(i, j), p = at(i, j);
            z_[p] = scene.z[k];
            const double n_manning = scene.manning_n.empty() ? def.default_manning_n : scene.manning_n[k];
            g_n2_[p] = def.gravity * n_manning * n_manning;
            const double eta0 = scene.eta0.empty() ? 0.0 : scene.eta0[k];
            const double h = std::max(0.0, eta0 - z_[p]);
            h_[p] = h;
            if (!scene.u0.empty() && h > def.dry_depth) {
                hu_[p] = h * scene.u0[k];
                hv_[p] = h * scene.v0[k];
            }
        }
    // Bed in the ghost cells: mirrored at walls (a lake at rest stays exact), copied elsewhere.
    for (Side s : {Side::west, Side::east, Side::south, Side::north}) {
        const bool mirror = boundary(s).kind == BoundaryKind::wall || boundary(s).kind == BoundaryKind::pump;
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
    track_transfer_ = def.west.kind == BoundaryKind::nested || def.east.kind == BoundaryKind::nested;
    for (auto* v : {&west_face_mass_, &east_face_mass_, &west_stage1_, &east_stage1_, &west_transfer_, &east_transfer_})
        v->assign(std::size_t(grid_.ny), 0.0);
}

const BoundaryDef& Solver::boundary(Side s) const {
    switch (s) {
        case Side::west: return def_.west;
        case Side::east: return def_.east;
        case Side::south: return def_.south;
        case Side::north: return def_.north;
    }
    return def_.west;
}


double Solver::volume() const {
    double v = 0.0;  // serial: the same sum whatever the thread count
    for (int j = 0; j < grid_.ny; ++j)
        for (int i = 0; i < grid_.nx; ++i) v += h_[at(i, j)];
    return v * grid_.dx * grid_.dy;
}

double Solver::stable_dt() const {
    const double g = def_.gravity, dry = def_.dry_depth, idx = 1.0 / grid_.dx, idy = 1.0 / grid_.dy;
    double amax = 0.0;
#pragma omp parallel for reduction(max : amax) schedule(static)
    for (int j = 0; j < grid_.ny; ++j) {
        const std::size_t row = at(0, j);
        const double* h = h_.data() + row;
        const double* hu = hu_.data() + row;
        const double* hv = hv_.data() + row;
        double a = 0.0;
#pragma omp simd reduction(max : a)
        for (int i = 0; i < grid_.nx; ++i) {
            const double c = std::sqrt(g * h[i]);
            const double inv = h[i] > dry ? 1.0 / h[i] : 0.0;
            a = std::max(a, (std::abs(hu[i]) * inv + c) * idx + (std::abs(hv[i]) * inv + c) * idy);
        }
        amax = std::max(amax, a);
    }
    return amax > 0.0 ? std::min(def_.max_dt, def_.cfl / amax) : def_.max_dt;
}

void Solver::fill_side(Side s, std::vector<double>& h, std::vector<double>& hu, std::vector<double>& hv, double t) {
    const SideForcing forcing = forcing_.at(s, t, [&] {
        double sum = 0.0;
        for (auto [i, j] : forcing_.pump_cells()) sum += h_[at(i, j)] + z_[at(i, j)];
        return sum / double(forcing_.pump_cells().size());
    });
    const BoundaryKind kind = forcing.kind;
    const bool xs = is_x_side(s);
    const int n_along = xs ? grid_.ny : grid_.nx;
    if (kind == BoundaryKind::nested) {
        const NestedGhosts& ng = nested_[s == Side::west ? 0 : 1];
        if (ng.a.h.size() != std::size_t(kGhost * n_along)) fail("", "boundary nested", "ghost values were not set before stepping");
        const double w = ng.t1 > ng.t0 ? std::clamp((t - ng.t0) / (ng.t1 - ng.t0), 0.0, 1.0) : 0.0;
        for (int layer = 1; layer <= kGhost; ++layer)
            for (int k = 0; k < n_along; ++k) {
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
    for (int k = 0; k < n_along; ++k) {
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
                case BoundaryKind::transmissive: {
                    const std::size_t src = cell(0);
                    h[ghost] = h[src];
                    qn[ghost] = qn[src];
                    qt[ghost] = qt[src];
                    break;
                }
                case BoundaryKind::level:
                case BoundaryKind::discharge: {
                    const std::size_t src = cell(0);
                    const double h_in = h[src];
                    const double un_in = sign * velocity(h_in, qn[src], def_.dry_depth);
                    const double ut_in = velocity(h_in, qt[src], def_.dry_depth);
                    double hb = 0.0, unb = 0.0;
                    open_side_state(forcing, h_in, un_in, std::max(0.0, -z_[src]), g, def_.dry_depth, hb, unb);
                    h[ghost] = hb;
                    qn[ghost] = sign * hb * unb;
                    qt[ghost] = hb * ut_in;
                    break;
                }
                case BoundaryKind::pump:
                case BoundaryKind::nested: break;  // resolved above
            }
        }
    }
}

void Solver::fill_ghosts(std::vector<double>& h, std::vector<double>& hu, std::vector<double>& hv, double t) {
    for (Side s : {Side::west, Side::east, Side::south, Side::north}) fill_side(s, h, hu, hv, t);
}

// x-direction: slopes, face fluxes and the cell rates of one interior row. Row buffers
// keep everything in cache; the loops are branch-free so they vectorise.
void Solver::x_sweep_row(int j, const std::vector<double>& h_all) {
    const std::size_t row = std::size_t(j + kGhost) * stride_;
    const int n = int(stride_);
    const double* __restrict e = eta_.data() + row;
    const double* __restrict h = h_all.data() + row;
    const double* __restrict u = u_.data() + row;
    const double* __restrict v = v_.data() + row;
    double* __restrict dh = dh_.data() + row;
    double* __restrict dhu = dhu_.data() + row;
    double* __restrict dhv = dhv_.data() + row;
    thread_local std::vector<double> buffer;
    if (buffer.size() != 8 * stride_) buffer.assign(8 * stride_, 0.0);
    double* __restrict se = buffer.data();
    double* __restrict sh = se + stride_;
    double* __restrict su = sh + stride_;
    double* __restrict sv = su + stride_;
    double* __restrict fm = sv + stride_;
    double* __restrict fl = fm + stride_;
    double* __restrict fr = fl + stride_;
    double* __restrict ft = fr + stride_;
    const double theta = def_.limiter_theta, dry = def_.dry_depth, g = def_.gravity;
    // Slopes; zero (first order) next to a dry cell, which keeps h >= 0 and the
    // shoreline at rest. Order 1: the weight is zero everywhere.
    const double order_weight = def_.order == 2 ? 1.0 : 0.0;
    #pragma omp simd
    for (int c = 1; c < n - 1; ++c) {
        const bool wet = (h[c - 1] > dry) & (h[c] > dry) & (h[c + 1] > dry);
        const double w = wet ? order_weight : 0.0;
        se[c] = w * limited_slope(e[c] - e[c - 1], e[c + 1] - e[c], theta);
        sh[c] = w * limited_slope(h[c] - h[c - 1], h[c + 1] - h[c], theta);
        su[c] = w * limited_slope(u[c] - u[c - 1], u[c + 1] - u[c], theta);
        sv[c] = w * limited_slope(v[c] - v[c - 1], v[c + 1] - v[c], theta);
    }
    // Face c+1/2 between padded columns c and c+1; interior faces c = 1 .. nx+1.
    #pragma omp simd
    for (int c = 1; c <= grid_.nx + 1; ++c) {
        FaceFlux f;
        face_flux(e[c] + 0.5 * se[c], h[c] + 0.5 * sh[c], u[c] + 0.5 * su[c], v[c] + 0.5 * sv[c], e[c + 1] - 0.5 * se[c + 1],
                  h[c + 1] - 0.5 * sh[c + 1], u[c + 1] - 0.5 * su[c + 1], v[c + 1] - 0.5 * sv[c + 1], g, f);
        fm[c] = f.mass;
        fl[c] = f.normal_L;
        fr[c] = f.normal_R;
        ft[c] = f.tangential;
    }
    west_face_mass_[std::size_t(j)] = fm[1];
    east_face_mass_[std::size_t(j)] = fm[grid_.nx + 1];
    const double idx = 1.0 / grid_.dx;
    #pragma omp simd
    for (int c = kGhost; c < grid_.nx + kGhost; ++c) {
        const double hw = h[c] - 0.5 * sh[c], he = h[c] + 0.5 * sh[c];
        const double zw = e[c] - 0.5 * se[c] - hw, ze = e[c] + 0.5 * se[c] - he;
        dh[c] = -(fm[c] - fm[c - 1]) * idx;
        dhu[c] = -(fl[c] - fr[c - 1]) * idx - g * 0.5 * (hw + he) * (ze - zw) * idx;
        dhv[c] = -(ft[c] - ft[c - 1]) * idx;
    }
}

void Solver::rates(std::vector<double>& h, std::vector<double>& hu, std::vector<double>& hv, double t) {
    fill_ghosts(h, hu, hv, t);
    const double dry = def_.dry_depth, g = def_.gravity, theta = def_.limiter_theta;
    const int nx = grid_.nx, ny = grid_.ny;
    const int s = int(stride_);
#pragma omp parallel
    {
        flush_subnormals();
#pragma omp for schedule(static)
        for (int r = 0; r < int(rows_); ++r) {
            const std::size_t row = std::size_t(r) * stride_;
            #pragma omp simd
            for (int c = 0; c < s; ++c) {
                const std::size_t p = row + std::size_t(c);
                eta_[p] = h[p] + z_[p];
                const double inv = h[p] > dry ? 1.0 / h[p] : 0.0;  // zero velocity where dry
                u_[p] = hu[p] * inv;
                v_[p] = hv[p] * inv;
            }
        }
#pragma omp for schedule(static)
        for (int j = 0; j < ny; ++j) x_sweep_row(j, h);

        // y-slopes on cell rows -1 .. ny (padded rows 1 .. ny+2), interior columns.
        if (def_.order == 2) {
#pragma omp for schedule(static)
            for (int r = 1; r <= ny + 2; ++r) {
                const std::size_t p0 = std::size_t(r) * stride_ + kGhost;
                #pragma omp simd
                for (int i = 0; i < nx; ++i) {
                    const std::size_t p = p0 + std::size_t(i), pm = p - stride_, pp = p + stride_;
                    const bool wet = h[pm] > dry && h[p] > dry && h[pp] > dry;
                    const double w = wet ? 1.0 : 0.0;
                    sy_eta_[p] = w * limited_slope(eta_[p] - eta_[pm], eta_[pp] - eta_[p], theta);
                    sy_h_[p] = w * limited_slope(h[p] - h[pm], h[pp] - h[p], theta);
                    sy_u_[p] = w * limited_slope(u_[p] - u_[pm], u_[pp] - u_[p], theta);
                    sy_v_[p] = w * limited_slope(v_[p] - v_[pm], v_[pp] - v_[p], theta);
                }
            }
        }
        // y-faces: face stored at the upper cell's index, between padded rows r-1 and r.
#pragma omp for schedule(static)
        for (int r = kGhost; r <= ny + kGhost; ++r) {
            const std::size_t p0 = std::size_t(r) * stride_ + kGhost;
            #pragma omp simd
            for (int i = 0; i < nx; ++i) {
                const std::size_t p = p0 + std::size_t(i), pm = p - stride_;
                FaceFlux f;
                face_flux(eta_[pm] + 0.5 * sy_eta_[pm], h[pm] + 0.5 * sy_h_[pm], v_[pm] + 0.5 * sy_v_[pm], u_[pm] + 0.5 * sy_u_[pm],
                          eta_[p] - 0.5 * sy_eta_[p], h[p] - 0.5 * sy_h_[p], v_[p] - 0.5 * sy_v_[p], u_[p] - 0.5 * sy_u_[p], g, f);
                gy_mass_[p] = f.mass;
                gy_lo_[p] = f.normal_L;
                gy_hi_[p] = f.normal_R;
                gy_tan_[p] = f.tangential;
            }
        }
        const double idy = 1.0 / grid_.dy;
#pragma omp for schedule(static)
        for (int r = kGhost; r < ny + kGhost; ++r) {
            const std::size_t p0 = std::size_t(r) * stride_ + kGhost;
            #pragma omp simd
            for (int i = 0; i < nx; ++i) {
                const std::size_t p = p0 + std::size_t(i), pn = p + stride_;
                const double hs = h[p] - 0.5 * sy_h_[p], hn = h[p] + 0.5 * sy_h_[p];
                const double zs = eta_[p] - 0.5 * sy_eta_[p] - hs, zn = eta_[p] + 0.5 * sy_eta_[p] - hn;
                dh_[p] -= (gy_mass_[pn] - gy_mass_[p]) * idy;
                dhv_[p] -= (gy_lo_[pn] - gy_hi_[p]) * idy + g * 0.5 * (hs + hn) * (zn - zs) * idy;
                dhu_[p] -= (gy_tan_[pn] - gy_tan_[p]) * idy;
            }
        }
    }
    add_sources(t);
}

void Solver::add_sources(double t) {
    const double rate = forcing_.pump_rate(t);  // [m/s] over the source strip
    if (rate == 0.0) return;
    for (auto [i, j] : forcing_.pump_cells()) dh_[at(i, j)] += rate;
}

void Solver::update(double dt, double a, const std::vector<double>* h0, const std::vector<double>* hu0, const std::vector<double>* hv0,
                    const std::vector<double>& h, const std::vector<double>& hu, const std::vector<double>& hv, std::vector<double>& h_out,
                    std::vector<double>& hu_out, std::vector<double>& hv_out) {
    if (def_.friction == Friction::explicit_)
        update_stage<Friction::explicit_>(dt, a, h0, hu0, hv0, h, hu, hv, h_out, hu_out, hv_out);
    else
        update_stage<Friction::implicit>(dt, a, h0, hu0, hv0, h, hu, hv, h_out, hu_out, hv_out);
}

template <Friction friction>
void Solver::update_stage(double dt, double a, const std::vector<double>* h0, const std::vector<double>* hu0,
                          const std::vector<double>* hv0, const std::vector<double>& h, const std::vector<double>& hu,
                          const std::vector<double>& hv, std::vector<double>& h_out, std::vector<double>& hu_out,
                          std::vector<double>& hv_out) {
    const double dry = def_.dry_depth;
    const int nx = grid_.nx;
    long fixes = 0;
    double worst = 0.0;
#pragma omp parallel for reduction(+ : fixes) reduction(min : worst) schedule(static)
    for (int j = 0; j < grid_.ny; ++j) {
        const std::size_t p0 = at(0, j);
#pragma omp simd reduction(+ : fixes) reduction(min : worst)
        for (int i = 0; i < nx; ++i) {
            const std::size_t p = p0 + std::size_t(i);
            double hn = h[p] + dt * dh_[p];
            double qx = hu[p] + dt * dhu_[p];
            double qy = hv[p] + dt * dhv_[p];
            if (hn < 0.0) {  // only round-off under the CFL bound; counted, then removed
                worst = std::min(worst, hn);
                ++fixes;
                hn = 0.0;
            }
            if constexpr (friction == Friction::explicit_) {  // study only: forward Euler on the old state
                const double e = explicit_friction_rate(h[p], hu[p], hv[p], g_n2_[p], dt, dry);
                qx -= e * hu[p];
                qy -= e * hv[p];
            } else {
                const double r = friction_factor(hn, qx, qy, g_n2_[p], dt, dry);
                qx *= r;
                qy *= r;
            }
            if (h0) {
                hn = a * (*h0)[p] + (1.0 - a) * hn;
                qx = a * (*hu0)[p] + (1.0 - a) * qx;
                qy = a * (*hv0)[p] + (1.0 - a) * qy;
                if (hn <= dry) qx = qy = 0.0;
            }
            h_out[p] = hn;
            hu_out[p] = qx;
            hv_out[p] = qy;
        }
    }
    stats_.negative_depth_fixes += fixes;
    stats_.min_depth_seen = std::min(stats_.min_depth_seen, worst);
}

void Solver::set_nested_ghosts(Side side, double t0, const GhostState& a, double t1, const GhostState& b) {
    if (!is_x_side(side) || boundary(side).kind != BoundaryKind::nested) fail("", "boundary nested", "ghosts given for a side that is not nested");
    const std::size_t n = std::size_t(kGhost * grid_.ny);
    for (const GhostState* g : {&a, &b})
        if (g->h.size() != n || g->hu.size() != n || g->hv.size() != n) fail("", "boundary nested", "ghost arrays of the wrong size");
    NestedGhosts& ng = nested_[side == Side::west ? 0 : 1];
    ng.t0 = t0;
    ng.t1 = t1;
    ng.a = a;
    ng.b = b;
}

void Solver::set_ghost_bed(Side side, const std::vector<double>& z) {
    if (!is_x_side(side) || z.size() != std::size_t(kGhost * grid_.ny)) fail("", "boundary nested", "ghost bed of the wrong size or side");
    for (int layer = 1; layer <= kGhost; ++layer)
        for (int j = 0; j < grid_.ny; ++j)
            z_[at(side == Side::west ? -layer : grid_.nx - 1 + layer, j)] = z[std::size_t((layer - 1) * grid_.ny + j)];
}

void Solver::reset_side_transfer() {
    std::fill(west_transfer_.begin(), west_transfer_.end(), 0.0);
    std::fill(east_transfer_.begin(), east_transfer_.end(), 0.0);
}

void Solver::step(double dt) {
    // Boundary mass transfer with the stepper's weights: Heun's U^{n+1} = U^n + dt/2 (L(U^n) + L(U^1)).
    if (def_.order == 1) {
        rates(h_, hu_, hv_, time_);
        if (track_transfer_)
            for (std::size_t j = 0; j < west_transfer_.size(); ++j) {
                west_transfer_[j] += dt * west_face_mass_[j];
                east_transfer_[j] += dt * east_face_mass_[j];
            }
        update(dt, 0.0, nullptr, nullptr, nullptr, h_, hu_, hv_, h_, hu_, hv_);
    } else {
        rates(h_, hu_, hv_, time_);
        if (track_transfer_) {
            west_stage1_ = west_face_mass_;
            east_stage1_ = east_face_mass_;
        }
        update(dt, 0.0, nullptr, nullptr, nullptr, h_, hu_, hv_, h1_, hu1_, hv1_);
        rates(h1_, hu1_, hv1_, time_ + dt);
        if (track_transfer_)
            for (std::size_t j = 0; j < west_transfer_.size(); ++j) {
                west_transfer_[j] += 0.5 * dt * (west_stage1_[j] + west_face_mass_[j]);
                east_transfer_[j] += 0.5 * dt * (east_stage1_[j] + east_face_mass_[j]);
            }
        // U = 1/2 U + 1/2 (U1 + dt L(U1)); each cell reads its own base value before writing it.
        update(dt, 0.5, &h_, &hu_, &hv_, h1_, hu1_, hv1_, h_, hu_, hv_);
    }
    time_ += dt;
    ++stats_.steps;
}

}  // namespace flotsam::hydro
