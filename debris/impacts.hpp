// Impacts of a body on buildings: when a contact is an impact, and the force a design
// standard assigns to it (docs/debris.md, "Impacts on buildings").
//
// The force. A body of mass m_d that strikes a wall at speed u and crushes like a linear
// spring of stiffness k (its own: the wall is taken as far stiffer) stops when its kinetic
// energy is stored in the spring, ½ k x² = ½ m_d u², where the spring force is largest:
//
//     F = k x = u √(k m_d).
//
// ASCE/SEI 7-16 Section 6.11 takes this as the nominal maximum instantaneous debris impact
// force, F_ni = u_max √(k m_d), and the design force as F_i = I_tsu C_o F_ni, with the
// orientation factor C_o = 0.65 (debris seldom strikes square along its stiff axis) and
// the importance factor I_tsu (1.0 for Risk Category II, 1.25 for III and IV: a property
// of the building hit, taken as 1 here). For a static analysis the standard multiplies by
// the dynamic response ratio R_max of the struck member (from the impulse duration
// t_d = 2 m_d u_max / F_ni against the member's natural period), also a property of the
// building: not applied (R_max = 1, the instantaneous force). In place of the standard's
// u_max, the flow speed at the site, the simulation gives the body's own approach speed
// along the contact normal, u_n, just before the impulse:
//
//     F = C_o u_n √(k m_d),   C_o = 0.65,   [N] = [m s⁻¹] √([N m⁻¹] [kg]).
//
// FEMA P-646 (2019) writes the same spring estimate as F_i = 1.3 u_max √(k m_d (1 + c)),
// with 1.3 an importance factor and c the hydrodynamic mass coefficient of the water
// that moves with the debris (fema_p646_impact_force, for comparison).
//
// The stiffness k is the body's (BodyDef::impact_stiffness, from the catalogue with its
// source; by Froude from the paper's box where the body is not in the catalogue: k scales
// as force / length, L²).
//
// One impact is one approach (an "event"), not every step of a contact: a body pushed
// against a wall by the flow touches it at nearly every step (each impulse sends it a
// micrometre off and the flow brings it back), which is one resting contact. So a contact
// with building b opens an episode, which is an impact where its approach speed u_n exceeds
// impact_speed_threshold (× √(L / 0.25 m)); the episode stays open while the body is within
// impact_separation_lengths × L of b after a step, and only a contact after the body has
// been farther than that from b can be a new impact.
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

#include "debris/kernels.hpp"
#include "formats/impact_file.hpp"

namespace flotsam::debris {

inline constexpr double asce7_orientation_factor = 0.65;  // C_o, ASCE/SEI 7-16 Section 6.11 [-]

// F = C_o u_n √(k m_d) [N]: speed [m/s], mass [kg], stiffness [N/m].
inline double impact_force(double speed, double mass, double stiffness) {
    return asce7_orientation_factor * speed * std::sqrt(stiffness * mass);
}
// FEMA P-646 (2019): F_i = 1.3 u √(k m_d (1 + c)) [N]; c the hydrodynamic mass coefficient [-].
inline double fema_p646_impact_force(double speed, double mass, double stiffness, double c) {
    return 1.3 * speed * std::sqrt(stiffness * mass * (1.0 + c));
}
// The formula as the files and docs state it.
inline constexpr const char* impact_force_formula =
    "ASCE/SEI 7-16 Section 6.11: F = C_o u sqrt(k m_d), C_o = 0.65, I_tsu = 1, R_max = 1 (instantaneous); u the approach "
    "speed along the contact normal, k the body's stiffness, m_d its mass";

// An approach slower than this (for the paper's 0.25 m box; × √(L / 0.25 m) by Froude) is
// a touch, not an impact: 1 cm/s, a third of the typical impact speed of the box on the 4 cm
// real layout (the buildings' median impact speeds: 0.011 to 0.13 m/s, 0.031 m/s in the
// middle; docs/debris.md, "Impacts on buildings") [m/s].
inline constexpr double impact_speed_threshold = 0.01;
// An episode of contact with a building ends once the body is this many body lengths
// clear of it (1 %: 2.5 mm for the box, a thousand times the micrometre of a resting
// contact's rebounds) [-].
inline constexpr double impact_separation_lengths = 0.01;
// The stiffness of a body with none given: the paper's full-scale box's (FEMA P-646's
// wood-log value, 2.4e6 N/m at L = 62.5 m) × (L / 62.5 m)² (Froude) [N/m].
inline double default_impact_stiffness(double length) { return 2.4e6 * (length / 62.5) * (length / 62.5); }

// A building touched in one step: the largest approach speed among its contacts at the
// pass where it was first seen, before that pass's impulses, and that contact's point.
struct BuildingTouch {
    std::int32_t building = 0;
    double speed = 0.0;  // [m/s], > 0 approaching
    Vec2 point;          // [m], the world's frame
};

// A body's impacts (cold: written on events) and the buildings it is in contact with.
struct BodyImpacts {
    std::vector<std::int32_t> open;  // buildings whose contact episode is open
    std::vector<Impact> events;      // in the world's frame (World::impacts adds the origin)
};

}  // namespace flotsam::debris
