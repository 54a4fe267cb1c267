// Small, pure, point-wise kernels of the debris model: no loops over cells or bodies,
// no state. The loops that call them live in loads.cpp (drag), contact.cpp (friction),
// obstacles.cpp and collision.cpp. Every quantity is SI (m, s, kg, N, rad).
#pragma once
#include <cmath>

namespace flotsam::debris {

struct Vec2 {
    double x = 0.0;
    double y = 0.0;
};
inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
inline Vec2& operator+=(Vec2& a, Vec2 b) {
    a.x += b.x;
    a.y += b.y;
    return a;
}
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
// z-component of a × b.
inline double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
// ω ẑ × r: velocity of a point at r from the axis of a rotation at rate ω.
inline Vec2 spin(double omega, Vec2 r) { return {-omega * r.y, omega * r.x}; }
inline double norm(Vec2 a) { return std::sqrt(dot(a, a)); }
// The share of a move (shift, turn) that carries no corner of a body, `half_diagonal` from
// its centre, further than `most`: 1 where none goes further [-].
inline double share_within(Vec2 shift, double turn, double half_diagonal, double most) {
    const double reach = norm(shift) + std::fabs(turn) * half_diagonal;
    return reach > most ? most / reach : 1.0;
}
inline Vec2 rotate(Vec2 a, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return {c * a.x - s * a.y, s * a.x + c * a.y};
}
// Two or four numbers at once (GCC/Clang vector types), for independent divisions in hot
// loops: a packed division gives each lane the correctly rounded quotient, the same bits
// as the scalar a / b, and the divider's latency is paid once.
using Double2 = double __attribute__((vector_size(16)));
using Double4 = double __attribute__((vector_size(32)));

// a / |a|, or zero below `eps` (no direction: a point that does not slide).
inline Vec2 unit_or_zero(Vec2 a, double eps) {
    const double n = norm(a);
    return n > eps ? Vec2{a.x / n, a.y / n} : Vec2{};
}

// Drag on one sampled face segment (extended Morison, after Ikeya et al. 2005):
//   F = ½ ρ C_d A |u_n| u_n n,  C_d = cd_toward where u_n < 0 (flow into the face),
//                               C_d = cd_away   where u_n ≥ 0 (flow leaving it).
// u_rel: fluid velocity minus the velocity of the face point [m/s]; normal: outward unit
// normal; area: segment length × wetted height [m²].
inline Vec2 face_drag(Vec2 u_rel, Vec2 normal, double area, double cd_toward, double cd_away, double rho) {
    const double un = dot(u_rel, normal);
    const double cd = un < 0.0 ? cd_toward : cd_away;
    return (0.5 * rho * cd * area * std::fabs(un) * un) * normal;
}

// Coulomb friction capacity of a patch of the bottom: μ times its share of the weight
// less buoyancy. area_fraction = S/(L B); depth: water depth over the patch [m]. Never
// negative (a patch deeper than the draft carries no load and is not in contact anyway).
inline double friction_capacity(double mu, double area_fraction, double mass, double rho, double plan_area, double depth,
                                double g) {
    const double load = (mass - rho * plan_area * depth) * g;
    return load > 0.0 ? mu * area_fraction * load : 0.0;
}

// The axis shift (paper Eqs. 7-10), about the contact-area centroid x_sub. arm: the
// centre relative to it, x_g − x_sub [m].
//
// Flow torque about x_sub from the force F and the torque T' about the centre (the flow
// force acts where it acts; only the lever changes): T_sub = T' + (x_g − x_sub) × F [N m].
inline double torque_about(double torque_centre, Vec2 force, Vec2 arm) { return torque_centre + cross(arm, force); }
// Yaw inertia about x_sub by the parallel-axis theorem, I_sub = I + M |x_g − x_sub|²: I
// the yaw inertia in use, M the translation's inertia (the added mass included, as the
// centre's motion on its arc carries it) [kg m²].
inline double parallel_axis_inertia(double inertia, double mass, Vec2 arm) { return inertia + mass * dot(arm, arm); }
// One step of I_sub dω_p/dt = T_sub, semi-implicit as the yaw about the centre: the rate at
// the end of the step from `rate` at its start [rad/s].
inline double pivot_rate_step(double rate, double torque_sub, double inertia_sub, double dt) {
    return rate + dt / inertia_sub * torque_sub;
}
// The centre's move by a turn Δθ_sub about x_sub (Eqs. 7-9):
// Δx_sub = x_g* − x_g^n = x_sub + R(Δθ_sub)(x_g^n − x_sub) − x_g^n = R arm − arm [m].
inline Vec2 pivot_shift(Vec2 arm, double turn) { return rotate(arm, turn) - arm; }

// Normal impulse against a fixed obstacle at a contact with normal n (into the body) and
// lever arm r from the centre: j = −(1 + e) v_n / (1/M + (r × n)² / I). Zero unless the
// contact point approaches the obstacle (v_n < 0), so a resting or separating contact
// gets nothing and the impulse can only remove kinetic energy for e ≤ 1.
inline double collision_impulse(double v_normal, double restitution, double mass, double inertia, Vec2 r, Vec2 n) {
    if (v_normal >= 0.0) return 0.0;
    const double rn = cross(r, n);
    return -(1.0 + restitution) * v_normal / (1.0 / mass + rn * rn / inertia);
}

// The move that takes a contact point out of an obstacle by `depth` along n (into the
// body), shared between translation and rotation as an impulse would be: a pseudo-impulse
// p = depth / (1/M + (r × n)² / I) moves the centre by p n / M and turns the body by
// p (r × n) / I, which to first order moves the point by exactly `depth` along n. A body
// held by two opposite contacts it cannot slide out of turns out of them instead.
struct SeparatingMove {
    Vec2 shift;         // [m]
    double turn = 0.0;  // [rad]
};
inline SeparatingMove separating_move(double depth, double mass, double inertia, Vec2 r, Vec2 n) {
    const double rn = cross(r, n);
    const double p = depth / (1.0 / mass + rn * rn / inertia);
    return {(p / mass) * n, p * rn / inertia};
}

}  // namespace flotsam::debris
