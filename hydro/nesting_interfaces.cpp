// The exchange across a nested run's interfaces (nesting.hpp): each grid's ghost cells
// from its neighbour's cells (copied between grids of one spacing, averaged from the
// finer grid, interpolated from the coarser one) and the refluxing that keeps the
// volume crossing an interface the same on both sides.
#include <algorithm>
#include <cmath>

#include "hydro/column_range.hpp"
#include "hydro/nesting.hpp"

namespace flotsam::hydro {

namespace {
constexpr int kLayers = kGhost;  // ghost layers of hydro::Solver (column_range.hpp)
}

template <class Real>
GhostState BasicNestedSolver<Real>::copied_ghosts(const Interface& f, bool from_west) const {
    const SlabSolver& from = slabs_[std::size_t(from_west ? f.west : f.west + 1)].solver;
    const int ny = from.grid().ny, nx = from.grid().nx;
    GhostState g;
    for (auto* v : {&g.h, &g.hu, &g.hv}) v->assign(std::size_t(kLayers * ny), 0.0);
    for (int L = 1; L <= kLayers; ++L)
        for (int j = 0; j < ny; ++j) {
            const int i = from_west ? nx - L : L - 1;  // layer 1 is the cell next to the interface
            const std::size_t q = std::size_t((L - 1) * ny + j);
            g.h[q] = from.depth(i, j);
            g.hu[q] = from.x_discharge(i, j);
            g.hv[q] = from.y_discharge(i, j);
        }
    return g;
}

template <class Real>
GhostState BasicNestedSolver<Real>::coarse_ghosts_from_fine(const Interface& f) const {
    if (f.same_grid) return copied_ghosts(f, !f.coarse_west);
    const SlabSolver& fine = slabs_[std::size_t(f.fine())].solver;
    const int rx = f.rx, ry = f.ry, ncy = slabs_[std::size_t(f.coarse())].solver.grid().ny, nxf = fine.grid().nx;
    GhostState g;
    for (auto* v : {&g.h, &g.hu, &g.hv}) v->assign(std::size_t(kLayers * ncy), 0.0);
    for (int L = 1; L <= kLayers; ++L)
        for (int J = 0; J < ncy; ++J) {
            double h = 0.0, hu = 0.0, hv = 0.0, wet_level = 0.0, wet_h = 0.0;
            int wet = 0;
            const int first = f.coarse_west ? (L - 1) * rx : nxf - L * rx;  // the fine cells under ghost layer L
            for (int b = 0; b < ry; ++b)
                for (int a = 0; a < rx; ++a) {
                    const int i = first + a, j = J * ry + b;
                    h += fine.depth(i, j);
                    hu += fine.x_discharge(i, j);
                    hv += fine.y_discharge(i, j);
                    if (fine.depth(i, j) > def_.dry_depth) {
                        ++wet;
                        wet_level += fine.level(i, j);
                        wet_h += fine.depth(i, j);
                    }
                }
            const std::size_t q = std::size_t((L - 1) * ncy + J);
            const double inv = 1.0 / double(rx * ry);
            g.h[q] = h * inv;
            g.hu[q] = hu * inv;
            g.hv[q] = hv * inv;
            if (wet > 0 && wet < rx * ry) {
                // Water beside dry fine ground (a shore, a building): the block's mean depth
                // over the ghost's mean ground would lift the level; the wet cells' level
                // over it keeps water at rest at rest (the reflux keeps the volume).
                const double depth = std::max(0.0, wet_level / wet - f.coarse_bed[q]);
                g.h[q] = depth;
                g.hu[q] = depth * hu / wet_h;
                g.hv[q] = depth * hv / wet_h;
            }
        }
    return g;
}

template <class Real>
GhostState BasicNestedSolver<Real>::fine_ghosts_from_coarse(const Interface& f) const {
    if (f.same_grid) return copied_ghosts(f, f.coarse_west);
    const SlabSolver& coarse = slabs_[std::size_t(f.coarse())].solver;
    const SlabSolver& fine = slabs_[std::size_t(f.fine())].solver;
    const Grid &cg = coarse.grid(), &fg = fine.grid();
    const int ny = fg.ny, I = f.coarse_west ? cg.nx - 1 : 0;  // the coarse column along the interface
    const double dry = def_.dry_depth;
    GhostState g;
    for (auto* v : {&g.h, &g.hu, &g.hv}) v->assign(std::size_t(kLayers * ny), 0.0);
    for (int j = 0; j < ny; ++j) {
        // Linear in y between the coarse row centres (held beyond the first and last);
        // from a single cell where a neighbour is dry.
        const double fy = std::clamp((fg.y(j) - cg.y0) / cg.dy, 0.0, double(cg.ny - 1));
        const int J0 = std::min(int(fy), cg.ny - 2 < 0 ? 0 : cg.ny - 2);
        const int J1 = std::min(J0 + 1, cg.ny - 1);
        double w = fy - J0;
        bool dry_source = false;  // the coarse cell the ghost takes is dry
        if (coarse.depth(I, J0) <= dry || coarse.depth(I, J1) <= dry) {
            w = w < 0.5 ? 0.0 : 1.0;
            dry_source = coarse.depth(I, w == 0.0 ? J0 : J1) <= dry;
        }
        const double eta = (1 - w) * coarse.level(I, J0) + w * coarse.level(I, J1);
        const double u = (1 - w) * coarse.x_velocity(I, J0) + w * coarse.x_velocity(I, J1);
        const double v = (1 - w) * coarse.y_velocity(I, J0) + w * coarse.y_velocity(I, J1);
        for (int L = 1; L <= kLayers; ++L) {
            const std::size_t q = std::size_t((L - 1) * ny + j);
            if (dry_source) {
                // The coarse grid sees dry ground here (a building or a shore averaged into
                // its cell): a wall for the fine water, whose level and flow along it the
                // ghost mirrors over its own ground.
                const int e = f.coarse_west ? L - 1 : fg.nx - L;
                const double he = fine.depth(e, j), h = he > dry ? std::max(0.0, fine.level(e, j) - f.fine_bed[q]) : 0.0;
                g.h[q] = h;
                g.hu[q] = h > dry ? -h * fine.x_velocity(e, j) : 0.0;
                g.hv[q] = h > dry ? h * fine.y_velocity(e, j) : 0.0;
                continue;
            }
            const double h = std::max(0.0, eta - f.fine_bed[q]);
            g.h[q] = h;
            g.hu[q] = h > dry ? h * u : 0.0;
            g.hv[q] = h > dry ? h * v : 0.0;
        }
    }
    return g;
}

template <class Real>
void BasicNestedSolver<Real>::reflux(const Interface& f) {
    SlabSolver& coarse = slabs_[std::size_t(f.coarse())].solver;
    const SlabSolver& fine = slabs_[std::size_t(f.fine())].solver;
    if (f.same_grid) {  // face by face, the same faces on both sides
        const std::vector<double>& tc = coarse.side_transfer(f.coarse_side());
        const std::vector<double>& tf = fine.side_transfer(f.fine_side());
        std::vector<double> dh(tc.size());
        for (std::size_t j = 0; j < dh.size(); ++j) dh[j] = (f.coarse_west ? tc[j] - tf[j] : tf[j] - tc[j]) / coarse.grid().dx;
        reflux_made_ += coarse.add_side_depth(f.coarse_side(), dh, reflux_clamps_);
        return;
    }
    const int ry = f.ry, ncy = coarse.grid().ny, I = f.coarse_west ? coarse.grid().nx - 1 : 0;
    // Transfers are positive toward +x: out of a coarse cell west of the interface, into
    // one east of it.
    const std::vector<double>& tc = coarse.side_transfer(f.coarse_side());
    const std::vector<double>& tf = fine.side_transfer(f.fine_side());
    const double dxc = coarse.grid().dx;
    std::vector<Real>& h = coarse.depth_data();
    for (int J = 0; J < ncy; ++J) {
        double fine_sum = 0.0;  // the fine faces along coarse row J, per unit length of it
        for (int b = 0; b < ry; ++b) fine_sum += tf[std::size_t(J * ry + b)];
        fine_sum /= double(ry);
        Real& hc = h[coarse.at(I, J)];
        hc += Real((f.coarse_west ? tc[std::size_t(J)] - fine_sum : fine_sum - tc[std::size_t(J)]) / dxc);
        if (hc < 0) {
            reflux_made_ -= double(hc) * dxc * coarse.grid().dy;
            hc = Real(0);
            ++reflux_clamps_;
        }
    }
}

// Both precisions (the rest of the class is instantiated in nesting.cpp).
template GhostState BasicNestedSolver<double>::coarse_ghosts_from_fine(const Interface&) const;
template GhostState BasicNestedSolver<float>::coarse_ghosts_from_fine(const Interface&) const;
template GhostState BasicNestedSolver<double>::fine_ghosts_from_coarse(const Interface&) const;
template GhostState BasicNestedSolver<float>::fine_ghosts_from_coarse(const Interface&) const;
template void BasicNestedSolver<double>::reflux(const Interface&);
template void BasicNestedSolver<float>::reflux(const Interface&);

}  // namespace flotsam::hydro
