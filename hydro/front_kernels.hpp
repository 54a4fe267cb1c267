// Point-wise kernels of the tracked fronts (docs/hydro.md, "Wet/dry fronts").
// The loops that drive them are in front.cpp.
//
// Why a cell average loses a dry-bed front: in Ritter's fan the Riemann invariant
// R+ = u + 2c (c = sqrt(g h)) is the same everywhere, but averaging two states with the
// same R+ gives a smaller one (h u is concave in h along that curve). Next to the tip,
// where neighbouring depths differ by large factors, each update takes about 0.3 c off
// R+, and the thin water then runs slower than the fan's tip (2 c0). Two corrections,
// both needed (each alone leaves the front 7-8 cells behind at 400 cells):
//
// 1. The wet fraction alpha of a tip cell (the cell into which the front is moving):
//    its water is a wedge over the part alpha * dx next to its full upstream neighbour;
//    c falls linearly to zero at the tip, so h = k^2 (L - s)^2 / g over the wedge of
//    length L = dx + alpha dx that holds the two cells' water, m = k^2 L^3 / (3 g) per
//    unit width: k = sqrt(3 g m / L^3). The face between the two cells takes the wedge's
//    state there: c_f = k alpha dx, h_f = c_f^2 / g, u_f = R+ - 2 c_f. The tip cell's
//    face toward the dry side is shut (only the bed's reaction), and alpha grows at the
//    tip speed R+ / dx until the cell is full; what overflows starts the next cell.
// 2. The invariant correction, after each step: at a face where the flow expands into
//    water less than half as deep, momentum moves toward the thin side until its R+ is
//    the thick side's less what the bed slope and Manning friction take along the
//    characteristic in the crossing time dx / (u + c):
//      D = -g dz / lambda - u_b (a tau |u_b|) / (1 + a tau |u_b|),  tau = dx / lambda,
//    with a = g n^2 <h^-4/3> the mean along the linear depth profile between the two
//    depths. A momentum exchange between two cells, so it conserves momentum; over a
//    lake at rest (u = 0) it never acts.
#pragma once
#include <algorithm>
#include <cmath>

#include "hydro/swe_kernels.hpp"

namespace flotsam::hydro {

// Mean of h^(-4/3) along the linear profile from depth a to depth b (both > 0):
// 3 (lo^(-1/3) - hi^(-1/3)) / (hi - lo); where the two are within 0.1 % the midpoint's
// h^(-4/3) (within 1e-7 of the mean), since the difference of two roots, each good to
// ~1e-11 (inverse_cube_root), would cancel there.
inline double mean_inverse_depth_43(double a, double b) {
    const double hi = std::max(a, b), lo = std::min(a, b);
    if (hi - lo <= 1e-3 * hi) {
        const double r = inverse_cube_root(0.5 * (hi + lo));
        return r * r * r * r;
    }
    return 3.0 * (inverse_cube_root(lo) - inverse_cube_root(hi)) / (hi - lo);
}

// The fall of R+ (<= 0) from a cell (velocity u toward the front, celerity c, invariant
// R = u + 2c, depth h) to a point `dist` downstream [m] where the bed has risen by dz [m]
// and the water is h_far deep, under Manning g n^2 = g_n2 [m s^-2 s^2 m^-2/3]: the bed
// slope's -g dz / lambda and the friction's velocity loss over the crossing time
// dist / lambda (the exact solution of du/dt = -a u |u|, so never more than u). At most
// the whole of R (a tip may stop, not turn back); none where R <= 0.
inline double invariant_drop(double g, double u, double c, double R, double h, double h_far, double dz, double dist, double g_n2,
                             double dry_depth) {
    const double Rp = std::max(R, 0.0);
    const double lambda = std::max(0.5 * (u + c + Rp), 1e-12);
    const double ub = 0.5 * (u + Rp);
    const double a = g_n2 * mean_inverse_depth_43(std::max(h, dry_depth), std::max(std::min(h_far, h), dry_depth));
    const double x = a * (dist / lambda) * std::abs(ub);
    return std::max(std::min(0.0, -g * dz / lambda - ub * x / (1.0 + x)), -Rp);
}

// A tip cell seen along one direction: the upstream (full) neighbour's depth, velocity
// toward the tip, bed; the tip cell's depth, wet fraction and bed; the cell length
// along the direction; g n^2 between the two.
struct TipInput {
    double h_up, u_up, z_up;     // [m], [m/s], [m]
    double h_tip, alpha, z_tip;  // [m], [-], [m]
    double dx;                   // [m]
    double g_n2;                 // [m^2/3 s^-2] g * manning_n^2
};

// The state of the face between the upstream cell and the tip cell (the wedge's there),
// seen from each side after the hydrostatic reconstruction over the face's mean bed, and
// the rate at which the wet fraction grows.
struct TipFace {
    double eta_up, h_up;    // upstream side of the face [m]
    double eta_tip, h_tip;  // tip side [m]
    double u;               // velocity toward the tip, both sides [m/s]
    double alpha_rate;      // d alpha / dt [1/s], >= 0
};

inline TipFace tip_face(const TipInput& in, double g, double dry_depth) {
    const double ell = std::clamp(in.alpha, 0.0, 1.0) * in.dx;
    const double span = in.dx + ell;
    const double k = std::sqrt(3.0 * g * (in.h_up + in.h_tip) * in.dx / (span * span * span));
    const double c_up = std::sqrt(g * in.h_up);
    const double R = in.u_up + 2.0 * c_up;
    // The wedge's own depth in the tip cell (its water over the wet part), for the friction.
    const double h_wet = in.h_tip / std::max(in.alpha, 1e-300);
    const double dist = 0.5 * in.dx + ell;  // upstream centre to the tip
    const double D =
        invariant_drop(g, in.u_up, c_up, R, in.h_up, h_wet, (in.z_tip - in.z_up) * dist / in.dx, dist, in.g_n2, dry_depth);
    const double R_face = R + (0.5 * in.dx / dist) * D;  // the drop up to the face
    // No deeper at the face than the water behind it, and never flowing back out of the
    // tip (a wedge only feeds its tip): either would let the face drain a cell past
    // empty within the CFL bound.
    const double c_f = std::min(k * ell, c_up), h_f = c_f * c_f / g;
    const double eta_f = 0.5 * (in.z_up + in.z_tip) + h_f;  // a level over the face's mean bed
    TipFace f;
    f.h_up = std::max(eta_f - in.z_up, 0.0);
    f.eta_up = in.z_up + f.h_up;
    f.h_tip = std::max(eta_f - in.z_tip, 0.0);
    f.eta_tip = in.z_tip + f.h_tip;
    f.u = std::max(R_face - 2.0 * c_f, 0.0);
    f.alpha_rate = std::max(R + D, 0.0) / in.dx;
    return f;
}

// The shut face of a tip cell toward the dry side: no mass or momentum crosses it; each
// side keeps the hydrostatic reconstruction's reaction g/2 (h^2 - h*^2) (zero on a flat
// bed), so a lake at rest against it stays at rest.
inline void shut_face_flux(double etaL, double hL, double etaR, double hR, double g, FaceFlux& f) {
    const double zs = std::max(etaL - hL, etaR - hR);
    const double hsL = std::max(0.0, etaL - zs), hsR = std::max(0.0, etaR - zs);
    f.mass = 0.0;
    f.tangential = 0.0;
    f.normal_L = 0.5 * g * (hL * hL - hsL * hsL);
    f.normal_R = 0.5 * g * (hR * hR - hsR * hsR);
}

// Whether a face between cells of depths a and b can take an invariant exchange: both
// wet, one less than half as deep as the other (invariant_exchange's kThin). Few faces
// pass, so this test runs first, in a pass that vectorises.
inline bool thin_beside_thick(double a, double b, double dry_depth) {
    return (a > dry_depth) & (b > dry_depth) & ((b < 0.5 * a) | (a < 0.5 * b));
}

// Whether a cell (depth h, bed z, wet fraction alpha) may be a tip, from its four
// neighbours' depths and beds (west, east, south, north): not full, and beside wet water
// that either reaches it (it holds water or a fraction) or stands above its ground. A
// superset of the tips; FrontTracker::find_tips looks closer at each.
inline bool may_be_tip(double h, double z, double alpha, double hw, double zw, double he, double ze, double hs, double zs, double hn,
                       double zn, double dry_depth) {
    const bool wet_w = hw > dry_depth, wet_e = he > dry_depth, wet_s = hs > dry_depth, wet_n = hn > dry_depth;
    const bool above = (wet_w & (hw + zw - z > dry_depth)) | (wet_e & (he + ze - z > dry_depth)) | (wet_s & (hs + zs - z > dry_depth)) |
                       (wet_n & (hn + zn - z > dry_depth));
    const bool holds = (h > dry_depth) | (alpha > 0.0);
    return (alpha < 1.0) & ((holds & (wet_w | wet_e | wet_s | wet_n)) | above);
}

// The wet fraction made consistent with the depths (FrontTracker::fix): 1 in a wet cell
// with no dry neighbour, 0 in a dry cell with no wet one; a wet cell's at least its depth
// over its deepest neighbour's (its wet part no deeper than the water beside it).
inline double consistent_wet_fraction(double alpha, double h, double hw, double he, double hs, double hn, double dry_depth) {
    const bool all_wet = (hw > dry_depth) & (he > dry_depth) & (hs > dry_depth) & (hn > dry_depth);
    const bool any_wet = (hw > dry_depth) | (he > dry_depth) | (hs > dry_depth) | (hn > dry_depth);
    const double deepest = std::max(std::max(hw, he), std::max(hs, hn));
    const double lowest = deepest > h ? h / deepest : 1.0;
    const double a = std::min(alpha, 1.0);
    const double wet_value = all_wet ? 1.0 : std::max(a, lowest);
    return h > dry_depth ? wet_value : (any_wet ? a : 0.0);
}

// The invariant correction at one face (both sides wetter than the dry tolerance):
// discharge [m^2/s] to move from the left cell to the right one (q_R += F, q_L -= F),
// from depths h, velocities u along the face normal, the bed rise z_R - z_L = dz, g n^2
// between the two and the cell length dx. Expanding flow only (u_R > u_L), into water
// less than half as deep; nothing when the thin side's invariant already stands at the
// thick side's plus the sources' drop, or above it.
inline double invariant_exchange(double hL, double uL, double hR, double uR, double dz, double g_n2, double dx, double g,
                                 double dry_depth) {
    constexpr double kThin = 0.5, kRoundOff = 1e-10;
    if (!(uR > uL)) return 0.0;
    const bool right = hR < kThin * hL && uR > 0.0, left = hL < kThin * hR && uL < 0.0;
    if (!right && !left) return 0.0;
    const double cL = std::sqrt(g * hL), cR = std::sqrt(g * hR);
    const double ub = 0.5 * (uL + uR), cb = 0.5 * (cL + cR);
    const double a = g_n2 * mean_inverse_depth_43(std::max(hL, dry_depth), std::max(hR, dry_depth));
    auto friction_loss = [&](double lambda) {  // velocity lost in the direction of ub over dx / lambda
        const double x = a * (dx / lambda) * std::abs(ub);
        return ub * x / (1.0 + x);
    };
    const double w = hL * hR / (hL + hR);
    if (right) {  // along C+, left to right: R+_R is lifted to R+_L + D
        const double lambda = std::max(ub + cb, 1e-12);
        const double D = std::min(0.0, -g * dz / lambda - friction_loss(lambda));
        const double gap = (uL + 2.0 * cL) + D - (uR + 2.0 * cR);
        return gap > kRoundOff * (std::abs(uL) + cL) ? gap * w : 0.0;
    }
    // C- from right to left (mirror): R-_L = R-_R + D'.
    const double lambda = std::max(cb - ub, 1e-12);
    const double D = std::max(0.0, -g * dz / lambda - friction_loss(lambda));
    const double gap = (uL - 2.0 * cL) - (uR - 2.0 * cR) - D;
    return gap > kRoundOff * (std::abs(uR) + cR) ? gap * w : 0.0;
}

}  // namespace flotsam::hydro
