// Point-wise kernels of the staggered leap-frog scheme (derivation: leapfrog.hpp). No
// loops, no storage; the loops that drive them live in leapfrog.cpp.
#pragma once
#include <algorithm>
#include <cmath>

#include "hydro/swe_kernels.hpp"

namespace flotsam::hydro {

// Whether the face between cells L and R (depths h, grounds z) carries flow this step:
// the side with the higher level is wet and that level stands more than the dry
// tolerance above the higher ground. Water below a roof's edge stays where it is.
inline bool face_open(double hL, double zL, double hR, double zR, double dry_depth) {
    const double etaL = hL + zL, etaR = hR + zR;
    const bool left_higher = etaL >= etaR;
    const double h_high = left_higher ? hL : hR;
    const double eta_high = left_higher ? etaL : etaR;
    return (h_high > dry_depth) & (eta_high - std::max(zL, zR) > dry_depth);
}

// Depth [m] that carries a face's mass flux for face velocity u: the upstream cell's
// level above the higher ground (0 when that cell is dry or its level is below it).
// Upstream depth makes the mass flux first-order upwind: at most the upstream cell's
// water crosses, so h stays >= 0 under the advective Courant bound.
inline double upstream_depth(double u, double hL, double zL, double hR, double zR, double dry_depth) {
    const bool from_left = u > 0.0;
    const double h_up = from_left ? hL : hR;
    const double d = (from_left ? hL + zL : hR + zR) - std::max(zL, zR);
    return (h_up > dry_depth) & (d > 0.0) ? d : 0.0;
}

// Momentum that mass fluxes bring into a face's momentum cell along one direction,
// per unit length [m^2/s^2 * m/m]: q_behind is the mean mass flux [m^2/s] through the
// side behind (the cell centre at -x of the face), carrying the velocity u_behind of the
// face beyond it when it flows in; likewise q_ahead at +x. Only inflow changes u:
// outflow takes the face's own velocity (momentum-conservative upwinding, Stelling &
// Duinmeijer 2003), so the update is a convex mix of neighbouring velocities.
inline double momentum_inflow(double q_behind, double u_behind, double q_ahead, double u_ahead, double u) {
    return std::max(q_behind, 0.0) * (u_behind - u) + std::max(-q_ahead, 0.0) * (u_ahead - u);
}

// One face over dt. From its old velocity u, the mean velocity across it u_across
// (the other component averaged onto the face) and the cells L and R on either side
// (depths h, grounds z, mean g n^2 of the two): the pressure gradient
// -g (eta_R - eta_L) / spacing, the momentum brought by inflow `inflow` [m^2/s^2]
// (momentum_inflow over the spacings) per face depth hb = (hL + hR) / 2, and Manning
// friction semi-implicit with the old speed:
//   u_new (1 + dt g n^2 |u| / hb^(4/3)) = u + dt (inflow / hb - g (eta_R - eta_L) / spacing)
// so friction only slows a face and never reverses it, however thin the film. A closed
// face (face_open) or one whose mean depth is dry gets u_new = 0. Returns u_new [m/s];
// `discharge` [m^2/s] gets upstream_depth(u_new) u_new.
inline double face_step(double u, double u_across, double hL, double zL, double hR, double zR, double g_n2, double spacing,
                        double inflow, double g, double dt, double dry_depth, double& discharge) {
    const double h_mean = 0.5 * (hL + hR);
    const double h = h_mean > dry_depth ? h_mean : 1.0;  // keeps the arithmetic finite; the result is 0 there
    const double y = inverse_cube_root(h), y2 = y * y;
    const double resistance = dt * g_n2 * std::sqrt(u * u + u_across * u_across) * (y2 * y2);  // dt g n^2 |u| / h^(4/3)
    const double level_step = (hR + zR) - (hL + zL);
    const double u_new = (u + dt * (inflow / h - g * level_step / spacing)) / (1.0 + resistance);
    const double u_out = (h_mean > dry_depth) & face_open(hL, zL, hR, zR, dry_depth) ? u_new : 0.0;
    discharge = upstream_depth(u_out, hL, zL, hR, zR, dry_depth) * u_out;
    return u_out;
}

// Factor in (0, 1] on the outgoing fluxes of a cell so that they take at most the
// water it holds: `outflow` is the depth [m] they would remove over the step.
inline double outflow_factor(double depth, double outflow) { return outflow > depth ? depth / outflow : 1.0; }

// The factor of the cell a face's flux q leaves (its upstream cell).
inline double upstream_factor(double q, double factor_L, double factor_R) { return q > 0.0 ? factor_L : factor_R; }

// Courant number of a cell for the step dt: dt sqrt(((|u| + c)/dx)^2 + ((|v| + c)/dy)^2),
// c = sqrt(g h). At rest it is c dt sqrt(1/dx^2 + 1/dy^2), whose limit 1 is the exact
// linear stability limit of the forward-backward C-grid; the flow speed is added to the
// wave speed per direction as for characteristics. The step is taken as stable while
// it stays at or below 1 (measured limits: docs/hydro.md).
inline double courant_number(double h, double u, double v, double g, double dt, double idx, double idy) {
    const double c = std::sqrt(g * h);
    const double ax = (std::abs(u) + c) * idx, ay = (std::abs(v) + c) * idy;
    return dt * std::sqrt(ax * ax + ay * ay);
}

}  // namespace flotsam::hydro
