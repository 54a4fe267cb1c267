// The solver's sides: the ghost cells of each boundary kind, the nested sides' ghosts and
// bed, and the depth a nested grid refluxes into an edge column.
#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "hydro/padded_rows.hpp"
#include "hydro/solver.hpp"
#include "hydro/swe_kernels.hpp"

namespace flotsam::hydro {

using padded::is_x_side;

template <class Real>
SideForcing BasicSolver<Real>::side_forcing(Side s, double t) {
    const SideForcing forcing = forcing_.at(s, t, [&] {
        double sum = 0.0;
        for (std::size_t p : pump_cells_) sum += double(now_.h[p]) + double(z_[p]);
        return sum / double(pump_cells_.size());
    });
    if (forcing.kind == BoundaryKind::nested) {
        const int n_along = is_x_side(s) ? grid_.ny : grid_.nx;
        if (nested_[s == Side::west ? 0 : 1].a.h.size() != std::size_t(kGhost * n_along))
            fail("", "boundary nested", "ghost values were not set before stepping");
    }
    return forcing;
}

template <class Real>
void BasicSolver<Real>::fill_side(Side s, Array& h, Array& hu, Array& hv, double t) {
    fill_side_cells(s, side_forcing(s, t), h, hu, hv, t, 0, is_x_side(s) ? grid_.ny : grid_.nx);
}

template <class Real>
void BasicSolver<Real>::fill_nested_cells(Side s, Array& h, Array& hu, Array& hv, double t, int k0, int k1) const {
    const int n_along = grid_.ny;
    const NestedGhosts& ng = nested_[s == Side::west ? 0 : 1];
    const double w = ng.t1 > ng.t0 ? std::clamp((t - ng.t0) / (ng.t1 - ng.t0), 0.0, 1.0) : 0.0;
    for (int layer = 1; layer <= kGhost; ++layer)
        for (int k = k0; k < k1; ++k) {
            const std::size_t ghost = at(s == Side::west ? -layer : grid_.nx - 1 + layer, k);
            const std::size_t q = std::size_t((layer - 1) * n_along + k);
            h[ghost] = Real((1.0 - w) * ng.a.h[q] + w * ng.b.h[q]);
            hu[ghost] = Real((1.0 - w) * ng.a.hu[q] + w * ng.b.hu[q]);
            hv[ghost] = Real((1.0 - w) * ng.a.hv[q] + w * ng.b.hv[q]);
        }
}

template <class Real>
void BasicSolver<Real>::fill_side_cells(Side s, const SideForcing& forcing, Array& h, Array& hu, Array& hv, double t, int k0,
                                        int k1) const {
    const BoundaryKind kind = forcing.kind;
    const bool xs = is_x_side(s);
    if (kind == BoundaryKind::nested) {
        fill_nested_cells(s, h, hu, hv, t, k0, k1);
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
        Array& qn = xs ? hu : hv;  // normal discharge
        Array& qt = xs ? hv : hu;  // tangential discharge
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
                    const double un_in = sign * velocity(h_in, double(qn[src]), def_.dry_depth);
                    const double ut_in = velocity(h_in, double(qt[src]), def_.dry_depth);
                    const double h0 =
                        kind == BoundaryKind::transmissive ? rest_depth_[int(s)][std::size_t(k)] : std::max(0.0, -double(z_[src]));
                    double hb = 0.0, unb = 0.0;
                    open_side_state(forcing, h_in, un_in, h0, g, def_.dry_depth, hb, unb);
                    h[ghost] = Real(hb);
                    qn[ghost] = Real(sign * hb * unb);
                    qt[ghost] = Real(hb * ut_in);
                    break;
                }
                case BoundaryKind::forced: {
                    const std::size_t src = cell(0);
                    const double h_in = h[src];
                    const double un_in = sign * velocity(h_in, double(qn[src]), def_.dry_depth);
                    const double ut_in = velocity(h_in, double(qt[src]), def_.dry_depth);
                    const double level = (*forcing.level)[std::size_t(k)];
                    const double depth = forcing.depth ? (*forcing.depth)[std::size_t(k)] : INFINITY;
                    double hb = 0.0, unb = 0.0, utb = ut_in;
                    if (forcing.u) {
                        const double u = (*forcing.u)[std::size_t(k)], v = (*forcing.v)[std::size_t(k)];
                        const double un_given = sign * (xs ? u : v), ut_given = xs ? v : u;
                        const double h_given = depth > def_.dry_depth ? std::max(0.0, level - double(z_[src])) : 0.0;
                        forced_ghost(h_in, un_in, ut_in, h_given, un_given, ut_given, g, hb, unb, utb);
                    } else if (depth > def_.dry_depth) {
                        level_ghost(h_in, un_in, std::max(0.0, -double(z_[src])), level, forcing.mode, g, hb, unb);
                    }
                    h[ghost] = Real(hb);
                    qn[ghost] = Real(sign * hb * unb);
                    qt[ghost] = Real(hb * utb);
                    break;
                }
                case BoundaryKind::pump:
                case BoundaryKind::nested:
                    break;  // resolved above
            }
        }
    }
}

template <class Real>
void BasicSolver<Real>::fill_ghosts(Array& h, Array& hu, Array& hv, double t) {
    for (Side s : {Side::west, Side::east, Side::south, Side::north}) fill_side(s, h, hu, hv, t);
}

template <class Real>
double BasicSolver<Real>::add_side_depth(Side side, const std::vector<double>& dh, long& clamps) {
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
        const double rate_before = cell_rate(now_.h[c], now_.hu[c], now_.hv[c]);
        now_.h[c] += Real(dh[std::size_t(j)]);
        if (now_.h[c] < 0) {
            made -= double(now_.h[c]) * grid_.dx * grid_.dy;
            now_.h[c] = Real(0);
            ++clamps;
        }
        if (now_.h[c] != 0.0) now_.bound[std::size_t(j)] = hull(now_.bound[std::size_t(j)], {i, i + 1});
        // The rate known from the last step stays the state's largest if it covers the
        // changed cells and none of them set it (so that a restart, which computes it
        // afresh, takes the same steps).
        const double rate = cell_rate(now_.h[c], now_.hu[c], now_.hv[c]);
        rate_lost = rate_lost || (rate_before == max_wave_rate_ && rate < rate_before);
        if (max_wave_rate_ >= 0.0) max_wave_rate_ = std::max(max_wave_rate_, rate);
        if (fronts && dh[std::size_t(j)] != 0.0) {
            const Array& alpha = now_.wet_fraction;
            inside_water = inside_water && now_.h[c] > dry && alpha[c] == 1.0 && alpha[std::size_t(std::ptrdiff_t(c) + inward)] == 1.0;
        }
    }
    // Cells that stay inside the water keep a wet fraction of 1 (front.hpp). Beside a
    // front the fractions depend on the depths: the next step makes them consistent
    // over the whole slab, as after any change from outside.
    if (fronts && !inside_water) changed_outside(now_.h);
    if (rate_lost) max_wave_rate_ = -1.0;
    return made;
}

template <class Real>
void BasicSolver<Real>::set_nested_ghosts(Side side, double t0, const GhostState& a, double t1, const GhostState& b) {
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

template <class Real>
void BasicSolver<Real>::set_ghost_bed(Side side, const std::vector<double>& z) {
    if (!is_x_side(side) || z.size() != std::size_t(kGhost * grid_.ny))
        fail("", "boundary nested", "ghost bed of the wrong size or side");
    for (int layer = 1; layer <= kGhost; ++layer)
        for (int j = 0; j < grid_.ny; ++j)
            z_[at(side == Side::west ? -layer : grid_.nx - 1 + layer, j)] = Real(z[std::size_t((layer - 1) * grid_.ny + j)]);
}

template SideForcing BasicSolver<double>::side_forcing(Side, double);
template SideForcing BasicSolver<float>::side_forcing(Side, double);
template void BasicSolver<double>::fill_ghosts(std::vector<double>&, std::vector<double>&, std::vector<double>&, double);
template void BasicSolver<float>::fill_ghosts(std::vector<float>&, std::vector<float>&, std::vector<float>&, double);
template void BasicSolver<double>::fill_side_cells(Side, const SideForcing&, std::vector<double>&, std::vector<double>&, std::vector<double>&,
                                                 double, int, int) const;
template void BasicSolver<float>::fill_side_cells(Side, const SideForcing&, std::vector<float>&, std::vector<float>&, std::vector<float>&,
                                                 double, int, int) const;
template double BasicSolver<double>::add_side_depth(Side, const std::vector<double>&, long&);
template double BasicSolver<float>::add_side_depth(Side, const std::vector<double>&, long&);
template void BasicSolver<double>::set_nested_ghosts(Side, double, const GhostState&, double, const GhostState&);
template void BasicSolver<float>::set_nested_ghosts(Side, double, const GhostState&, double, const GhostState&);
template void BasicSolver<double>::set_ghost_bed(Side, const std::vector<double>&);
template void BasicSolver<float>::set_ghost_bed(Side, const std::vector<double>&);

}  // namespace flotsam::hydro
