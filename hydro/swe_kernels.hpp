// Point-wise kernels of the shallow-water scheme: no loops, no storage, so each can be
// read and tested alone. The loops that drive them live in split_rows.hpp (the split
// step) and swe_rows.hpp (Heun's stages).
//
// Equations (docs/hydro.md, "Equations"), with h depth, q = (hu, hv) discharge, z bed,
// eta = h + z:
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
// Into dry ground (a side at most the dry tolerance deep) the flux is the exact
// dry-bed Riemann solution's at the face instead: HLL carries water onto dry land at
// half the fan's speed, and the front lags.
//
// Wet and dry: one tolerance eps (PhysicsDef::dry_depth, 1e-9 m). It desingularises the
// velocity, u = 2 h q / (h^2 + max(h^2, eps^2)) (q/h above eps, bounded by q/eps and
// vanishing with h below it), and switches the reconstruction to first order next to a
// cell below it, and where the ground cuts the surface (keeps_slope). It does not remove water or momentum: a thin layer keeps its discharge,
// so the water at a front moves on. What a cell average still loses at a dry-bed front
// (the thin water's speed) the front treatment restores (front_kernels.hpp, front.hpp).
//
// Friction: solved implicitly per cell for fixed h, |q| + a |q|^2 = |q*| with
// a = dt g n^2 / h^(7/3) (h held at eps below it), so it only slows the flow, never
// reverses it, and stays finite as h -> 0.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace flotsam::hydro {

// sqrt, abs, min and max unqualified in the kernels: std's for float and double, and a
// counting number type's own, found in its namespace (bench/hydro_limit.cpp counts the
// operations per cell).
using std::abs;
using std::max;
using std::min;
using std::sqrt;

// Whether a cell keeps the limited slopes s_eta, s_h of its level and depth along a
// direction (depth h, level eta = h + z; m before, 0 the cell, p after): all three wetter
// than the dry tolerance, and either the water covers the ground between them (at each of
// the cell's faces both sides' water stands above the higher bed: the first-order
// hydrostatic reconstruction is wet on both sides) or the bed the slopes imply at each
// face, z0 -+ (s_eta - s_h) / 2, stays between the beds of the two cells that share it.
//
// Where the ground cuts the surface, a neighbour's level is its film on its ground, and
// a slope through it can be a slope of the ground the cell does not have, or of the water
// beside a film: a puddle in a pit between two films, or a film on a flat shelf beside a
// puddle. The implied bed then leaves the ground's range: it tilts the cell (a force no
// flux balances), and the film's face, lifted above the puddle's level, shuts the outflow
// (a puddle ran at 1.4 m/s for minutes; docs/hydro.md, "A puddle in a pit"). On a slope
// the implied bed follows the ground, and a film running down it keeps its slope (first
// order there runs at a fifth of the normal-flow speed). Over a lake at rest, and wherever
// the water covers the ground, nothing changes.
template <class Real>
inline bool keeps_slope(Real hm, Real eta_m, Real h0, Real eta_0, Real hp, Real eta_p, Real s_eta, Real s_h, Real dry) {
    const Real zm = eta_m - hm, z0 = eta_0 - h0, zp = eta_p - hp;
    const bool wet = (hm > dry) & (h0 > dry) & (hp > dry);
    const bool covered = (min(eta_m, eta_0) - max(zm, z0) > dry) & (min(eta_p, eta_0) - max(zp, z0) > dry);
    const Real rise = Real(0.5) * (s_eta - s_h);  // of the implied bed, from the centre to the + face
    const Real face_m = z0 - rise, face_p = z0 + rise;
    const bool within = (face_m >= min(zm, z0) - dry) & (face_m <= max(zm, z0) + dry) &
                        (face_p >= min(zp, z0) - dry) & (face_p <= max(zp, z0) + dry);
    return wet & (covered | within);
}

// Generalised minmod limiter of the one-sided differences dl, dr: theta = 1 is minmod
// (most diffusive), theta = 2 is monotonised central (sharpest).
template <class Real>
inline Real limited_slope(Real dl, Real dr, Real theta) {
    const Real c = Real(0.5) * (dl + dr);
    const Real lo = min(min(theta * dl, c), theta * dr);
    const Real hi = max(max(theta * dl, c), theta * dr);
    // All three share a sign: take the one closest to zero; otherwise zero.
    return lo > Real(0) ? lo : (hi < Real(0) ? hi : Real(0));
}

// 1/h, desingularised below the dry tolerance eps: 2 h / (h^2 + max(h^2, eps^2)), which
// is 1/h for h >= eps and 2 h / (h^2 + eps^2) -> 0 as h -> 0, never above 1/eps.
template <class Real>
inline Real inverse_depth(Real h, Real eps) {
    return Real(2) * h / (h * h + max(h * h, eps * eps));
}

// Velocity from discharge: q/h, desingularised below the dry tolerance (inverse_depth),
// so a film of round-off depth has a bounded speed and dry ground none.
template <class Real>
inline Real velocity(Real h, Real q, Real dry_depth) {
    return q * inverse_depth(h, dry_depth);
}

// The CFL rate of a cell, (|u| + c) / dx + (|v| + c) / dy with c = sqrt(g h) [1/s]: a
// stable step is at most cfl over its largest value.
template <class Real>
inline Real wave_rate(Real h, Real hu, Real hv, Real g, Real dry_depth, Real idx, Real idy) {
    const Real c = sqrt(g * h);
    const Real inv = inverse_depth(h, dry_depth);
    return (abs(hu) * inv + c) * idx + (abs(hv) * inv + c) * idy;
}

// Numerical flux across one face, normal direction n, tangential t. Inputs are face
// values on the left (L) and right (R) side: level eta, depth h, normal velocity un,
// tangential velocity ut. Outputs: mass flux, normal-momentum flux as seen from the
// left cell and from the right cell (they differ by the hydrostatic corrections), and
// tangential-momentum flux. Returns the largest wave speed at the face.
template <class Real>
struct FaceFluxOf {
    Real mass;        // [m^2/s]
    Real normal_L;    // [m^3/s^2], for the cell on the left
    Real normal_R;    // [m^3/s^2], for the cell on the right
    Real tangential;  // [m^3/s^2]
};
using FaceFlux = FaceFluxOf<double>;

template <class Real>
[[gnu::always_inline]] inline Real face_flux(Real etaL, Real hL, Real unL, Real utL, Real etaR, Real hR, Real unR, Real utR, Real g, Real dry_depth,
                      FaceFluxOf<Real>& f) {
    const Real zL = etaL - hL, zR = etaR - hR;
    const Real zs = max(zL, zR);
    const Real hsL = max(Real(0), etaL - zs);
    const Real hsR = max(Real(0), etaR - zs);
    const Real cL = sqrt(g * hsL), cR = sqrt(g * hsR);
    const Real sL = min(min(unL - cL, unR - cR), Real(0));
    const Real sR = max(max(unL + cL, unR + cR), Real(0));
    const Real qL = hsL * unL, qR = hsR * unR;
    const Real pL = Real(0.5) * g * hsL * hsL, pR = Real(0.5) * g * hsR * hsR;
    const Real span = sR - sL;
    // Both sides dry: no wave, no flux.
    const Real inv = span > Real(1e-12) ? Real(1) / span : Real(0);
    const Real hll_mass = (sR * qL - sL * qR + sL * sR * (hsR - hsL)) * inv;
    const Real hll_normal = (sR * (qL * unL + pL) - sL * (qR * unR + pR) + sL * sR * (qR - qL)) * inv;
    // Into dry ground the flux is the dry-bed Riemann solution's at the face: one
    // rarefaction from the wet side, whose sonic state has u = c = (u_wet + 2 c_wet) / 3
    // (right side dry; mirrored for the left), h = c^2 / g, so mass h c and momentum
    // h c^2 + g h^2 / 2 = 1.5 h c^2; the wet side's flux when it is supercritical away
    // from the face; nothing when it moves away faster than 2 c. HLL there carries the
    // mass in at u + c/2 instead of the fan's mean speed u + c, and the front lags.
    // One fan, from whichever side is wet (s = +1: the right side is dry); 1/g, not a
    // division per face: these loops are bound by their divisions and roots.
    const bool dryL = hsL <= dry_depth, dryR = hsR <= dry_depth;
    const Real s = dryR ? Real(1) : Real(-1);
    const Real un_wet = dryR ? unL : unR, c_wet = dryR ? cL : cR, q_wet = dryR ? qL : qR, p_wet = dryR ? pL : pR;
    const Real cs = max(Real(0), (s * un_wet + Real(2) * c_wet) * Real(1.0 / 3.0)), hs = cs * cs * (Real(1) / g);
    const bool away = s * un_wet >= c_wet;  // supercritical toward the dry side: the wet side's own flux
    const Real dry_mass = away ? q_wet : s * hs * cs;
    const Real dry_normal = away ? q_wet * un_wet + p_wet : Real(1.5) * hs * cs * cs;
    const bool one_dry = dryL != dryR;
    const Real mass = one_dry ? dry_mass : hll_mass;
    const Real normal = one_dry ? dry_normal : hll_normal;
    f.mass = mass;
    // A wall: one side dry, its ground above where the other side's water would stand if
    // it were reflected there, max(h, h*) + z (h* the star depth of the Riemann problem
    // against the side's mirror image, two-rarefaction: sqrt(g h*) = sqrt(g h) + u/2 with
    // u toward the face; GeoClaw's solver tests the same). No water crosses it, and its
    // flux is the reflection's (HLL against the mirror image: normal momentum
    // p + q u + (|u| + c) q, never below zero) where the hydrostatic reconstruction alone
    // gives p: the reflected wave's reaction c q resists the water moving into a building.
    // At rest it is p (well balanced). Without it, steps above dt (|u| + c)/dx = 0.7 along
    // one direction grow round-off in a cell beside a building. Water that would rise
    // above the dry side's ground (a shore it runs up) meets no wall.
    // A wall needs one side wet and the other dry, so the full-depth speed sqrt(g h) of
    // the wet side is the only one either wall test reads: one root, not two (where no
    // wall can be, the other side's speed goes into a term weighted 0).
    const Real pfL = Real(0.5) * g * hL * hL, pfR = Real(0.5) * g * hR * hR;
    const Real cfL = sqrt(g * (hR > dry_depth ? hR : hL)), cfR = cfL;
    const Real starL = max(Real(0), cfL + Real(0.5) * unL), starR = max(Real(0), cfR - Real(0.5) * unR);
    const Real wallL = (hL > dry_depth) && !(hR > dry_depth) && max(hL, starL * starL * (Real(1) / g)) + zL < zR ? Real(1) : Real(0);
    const Real wallR = (hR > dry_depth) && !(hL > dry_depth) && max(hR, starR * starR * (Real(1) / g)) + zR < zL ? Real(1) : Real(0);
    const Real qfL = hL * unL, qfR = hR * unR;
    const Real reactL = max(-pfL, qfL * unL + (abs(unL) + cfL) * qfL);
    const Real reactR = max(-pfR, qfR * unR - (abs(unR) + cfR) * qfR);
    // Weights 0 or 1, not a select after the roots nor a bool converted: either keeps GCC
    // 12 from vectorising the face loops.
    f.normal_L = normal + (pfL - pL) + reactL * wallL;
    f.normal_R = normal + (pfR - pR) + reactR * wallR;
    f.tangential = mass * (mass > Real(0) ? utL : utR);
    return max(-sL, sR);
}

// h^(-1/3) for h > 0 without division or libm (libm's cbrt does not vectorise): a float
// bit trick gives a few per cent, three Newton steps y <- y (4 - h y^3) / 3 make it
// ~1e-11 relative.
template <class Real>
inline Real inverse_cube_root(Real h) {
    const float f = float(h);
    std::uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    bits = 0x54a2fa8cu - bits / 3u;
    float r;
    std::memcpy(&r, &bits, sizeof r);
    Real y = r;
    y = y * (Real(4) - h * y * y * y) * Real(1.0 / 3.0);
    y = y * (Real(4) - h * y * y * y) * Real(1.0 / 3.0);
    y = y * (Real(4) - h * y * y * y) * Real(1.0 / 3.0);
    return y;
}

// Implicit Manning friction on one discharge component pair (q1, q2) over dt:
// returns the factor r in (0, 1] with q_new = r q*. g_n2 = g * n^2. Below the dry
// tolerance the depth in the friction term is held at dry_depth: thin layers keep
// their (desingularised) momentum instead of losing all of it, and a stays finite.
template <class Real>
inline Real friction_factor(Real h, Real q1, Real q2, Real g_n2, Real dt, Real dry_depth) {
    const Real hs = max(h, dry_depth);
    const Real qmag = sqrt(q1 * q1 + q2 * q2);
    const Real y = inverse_cube_root(hs), y3 = y * y * y;
    const Real a = dt * g_n2 * (y3 * y3 * y);  // dt g n^2 / h^(7/3)
    // |q| = (-1 + sqrt(1 + 4 a |q*|)) / (2a), written without cancellation.
    return Real(2) / (Real(1) + sqrt(Real(1) + Real(4) * a * qmag));
}

// Explicit Manning friction, kept only for the stability study: q_new = q* - e q_old with
// e = dt g n^2 |q_old| / h_old^(7/3) from the old state (0 where dry). Where e > 1 the
// step reverses the flow, where e > 2 it grows it: thin films (h^(7/3) tiny) blow up.
inline double explicit_friction_rate(double h, double q1, double q2, double g_n2, double dt, double dry_depth) {
    const double hs = h > dry_depth ? h : 1.0;
    const double y = inverse_cube_root(hs), y3 = y * y * y;
    const double e = dt * g_n2 * sqrt(q1 * q1 + q2 * q2) * (y3 * y3 * y);
    return h > dry_depth ? e : 0.0;
}

}  // namespace flotsam::hydro
