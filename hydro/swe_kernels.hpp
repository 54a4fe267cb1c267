// Point-wise kernels of the shallow-water scheme: no loops, no storage, so each can be
// read and tested alone. The loops that drive them live in solver.cpp.
//
// Equations (MODEL.md), with h depth, q = (hu, hv) discharge, z bed, eta = h + z:
//
//   h_t + (hu)_x + (hv)_y = 0
//   (hu)_t + (hu^2 + g h^2/2)_x + (huv)_y = -g h z_x - g n^2 u |u| / h^(1/3)
//   (hv)_t + (huv)_x + (hv^2 + g h^2/2)_y = -g h z_y - g n^2 v |u| / h^(1/3)
//
// Space: finite volumes; in each cell the slopes of eta, h, u, v are limited
// (generalised minmod). Face values then give z = eta - h on each side. Reconstructing
// eta rather than z keeps a lake at rest exact: eta has zero slope there, so every face
// sees the same eta and the fluxes balance the bed source term to round-off.
//
// Hydrostatic reconstruction (Audusse et al. 2004, SIAM J. Sci. Comput. 25:2050): at a
// face with left/right face values (eta, h), take z* = max(z_L, z_R) and
// h*_L = max(0, eta_L - z*), h*_R = max(0, eta_R - z*). The numerical flux uses h*, and
// each side adds back g/2 (h_side^2 - h*_side^2) to its normal momentum flux. With the
// centred term -g (h_w + h_e)/2 (z_e - z_w) inside the cell this is well balanced and,
// with a positive flux (HLL) and dt * sum(a/dx) <= 1/2, keeps h >= 0.
//
// Flux: HLL for mass and normal momentum; the tangential momentum is carried upwind by
// the mass flux, which keeps shear layers (the port's eddies) sharper than plain HLL.
//
// Friction: solved implicitly per cell for fixed h, |q| + a |q|^2 = |q*| with
// a = dt g n^2 / h^(7/3), so it only slows the flow, never reverses it, and stays
// finite as h -> 0 (q -> 0 there).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace flotsam::hydro {

// Generalised minmod limiter of the one-sided differences dl, dr: theta = 1 is minmod
// (most diffusive), theta = 2 is monotonised central (sharpest).
inline double limited_slope(double dl, double dr, double theta) {
    const double c = 0.5 * (dl + dr);
    const double lo = std::min(std::min(theta * dl, c), theta * dr);
    const double hi = std::max(std::max(theta * dl, c), theta * dr);
    // All three share a sign: take the one closest to zero; otherwise zero.
    return lo > 0.0 ? lo : (hi < 0.0 ? hi : 0.0);
}

// Velocity from discharge; zero in dry cells so a film of round-off depth has no speed.
inline double velocity(double h, double q, double dry_depth) { return h > dry_depth ? q / h : 0.0; }

// The CFL rate of a cell, (|u| + c) / dx + (|v| + c) / dy with c = sqrt(g h) [1/s]: a
// stable step is at most cfl over its largest value.
inline double wave_rate(double h, double hu, double hv, double g, double dry_depth, double idx, double idy) {
    const double c = std::sqrt(g * h);
    const double inv = h > dry_depth ? 1.0 / h : 0.0;
    return (std::abs(hu) * inv + c) * idx + (std::abs(hv) * inv + c) * idy;
}

// Numerical flux across one face, normal direction n, tangential t. Inputs are face
// values on the left (L) and right (R) side: level eta, depth h, normal velocity un,
// tangential velocity ut. Outputs: mass flux, normal-momentum flux as seen from the
// left cell and from the right cell (they differ by the hydrostatic corrections), and
// tangential-momentum flux. Returns the largest wave speed at the face.
struct FaceFlux {
    double mass;        // [m^2/s]
    double normal_L;    // [m^3/s^2], for the cell on the left
    double normal_R;    // [m^3/s^2], for the cell on the right
    double tangential;  // [m^3/s^2]
};

inline double face_flux(double etaL, double hL, double unL, double utL, double etaR, double hR, double unR, double utR, double g,
                        FaceFlux& f) {
    const double zL = etaL - hL, zR = etaR - hR;
    const double zs = std::max(zL, zR);
    const double hsL = std::max(0.0, etaL - zs);
    const double hsR = std::max(0.0, etaR - zs);
    const double cL = std::sqrt(g * hsL), cR = std::sqrt(g * hsR);
    const double sL = std::min(std::min(unL - cL, unR - cR), 0.0);
    const double sR = std::max(std::max(unL + cL, unR + cR), 0.0);
    const double qL = hsL * unL, qR = hsR * unR;
    const double pL = 0.5 * g * hsL * hsL, pR = 0.5 * g * hsR * hsR;
    const double span = sR - sL;
    // Both sides dry: no wave, no flux.
    const double inv = span > 1e-12 ? 1.0 / span : 0.0;
    const double mass = (sR * qL - sL * qR + sL * sR * (hsR - hsL)) * inv;
    const double normal = (sR * (qL * unL + pL) - sL * (qR * unR + pR) + sL * sR * (qR - qL)) * inv;
    f.mass = mass;
    f.normal_L = normal + 0.5 * g * (hL * hL - hsL * hsL);
    f.normal_R = normal + 0.5 * g * (hR * hR - hsR * hsR);
    f.tangential = mass * (mass > 0.0 ? utL : utR);
    return std::max(-sL, sR);
}

// h^(-1/3) for h > 0 without division or libm (libm's cbrt does not vectorise): a float
// bit trick gives a few per cent, three Newton steps y <- y (4 - h y^3) / 3 make it
// ~1e-11 relative.
inline double inverse_cube_root(double h) {
    const float f = float(h);
    std::uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    bits = 0x54a2fa8cu - bits / 3u;
    float r;
    std::memcpy(&r, &bits, sizeof r);
    double y = r;
    y = y * (4.0 - h * y * y * y) * (1.0 / 3.0);
    y = y * (4.0 - h * y * y * y) * (1.0 / 3.0);
    y = y * (4.0 - h * y * y * y) * (1.0 / 3.0);
    return y;
}

// Implicit Manning friction on one discharge component pair (q1, q2) over dt:
// returns the factor r in (0, 1] with q_new = r q*. g_n2 = g * n^2.
inline double friction_factor(double h, double q1, double q2, double g_n2, double dt, double dry_depth) {
    // Dry: any finite r, multiplied by 0. (Written without a branch around the
    // arithmetic so that the loops calling this vectorise.)
    const double hs = std::max(h, dry_depth);
    const double qmag = std::sqrt(q1 * q1 + q2 * q2);
    const double y = inverse_cube_root(hs), y3 = y * y * y;
    const double a = dt * g_n2 * (y3 * y3 * y);  // dt g n^2 / h^(7/3)
    // |q| = (-1 + sqrt(1 + 4 a |q*|)) / (2a), written without cancellation.
    const double r = 2.0 / (1.0 + std::sqrt(1.0 + 4.0 * a * qmag));
    return r * (h > dry_depth ? 1.0 : 0.0);
}

// Explicit Manning friction, kept only for the stability study: q_new = q* - e q_old with
// e = dt g n^2 |q_old| / h_old^(7/3) from the old state (0 where dry). Where e > 1 the
// step reverses the flow, where e > 2 it grows it: thin films (h^(7/3) tiny) blow up.
inline double explicit_friction_rate(double h, double q1, double q2, double g_n2, double dt, double dry_depth) {
    const double hs = h > dry_depth ? h : 1.0;
    const double y = inverse_cube_root(hs), y3 = y * y * y;
    const double e = dt * g_n2 * std::sqrt(q1 * q1 + q2 * q2) * (y3 * y3 * y);
    return h > dry_depth ? e : 0.0;
}

}  // namespace flotsam::hydro
