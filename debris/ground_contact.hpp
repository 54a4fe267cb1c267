// Ground contact of one body (MODEL.md, "Friction" and "Axis shift"; docs/debris.md):
// the friction patches of centre contact (CC) or local contact (LC, paper Eqs. 4-5),
// Coulomb friction that never reverses the motion within a step, and the rotation
// about the contact centroid (paper Eqs. 6-10).
#pragma once
#include <vector>

#include "debris/body.hpp"
#include "debris/box.hpp"
#include "debris/flow_sampler.hpp"
#include "debris/footprint.hpp"
#include "debris/loads.hpp"

namespace flotsam::debris {

// One patch of the bottom in contact with the ground.
struct GroundPatch {
    Vec2 r;                 // overlap centroid relative to the centre [m]
    double area = 0.0;      // S_ij [m²]
    double capacity = 0.0;  // μ (S_ij / LB)(m − ρ L B h_ij) g [N]
};

// The patches in contact at time t for a body at `box`: CC, one patch at the centre when
// h_c < d; LC, one per grid cell under the footprint where h_ij < d (`footprint` keeps
// the last box's cells). Clears `out` first. `depth_bound`: first ask the reader for a
// lower bound of the depth under the body and return at once where even that is as deep
// as the draft (the same answer, sooner for a floating body; for a body that was grounded
// at its last step the bound seldom skips anything and costs a scan of the window).
void ground_patches(const FlowSampler& flow, const Grid& grid, const BodyParams& body, const Box& box, double centre_depth,
                     double t, double rho, double g, FootprintCache& footprint, std::vector<GroundPatch>& out,
                     bool depth_bound = true);

// Translational and yaw velocity.
struct Velocities {
    Vec2 V;              // [m/s]
    double omega = 0.0;  // [rad/s]
};

// Friction over one step from the trial velocities (after the flow force): each patch
// resists the sliding of its own point; a component that would change sign stops.
struct Friction {
    Velocities after;
    double capacity = 0.0;  // Σ of the patch capacities [N]
};
Friction apply_friction(const std::vector<GroundPatch>& patches, const Velocities& trial, const Inertia& eff, double dt);

// The axis shift of one step: the rotation about the contact centroid and the centre's
// move with it (x_g* − x_g^n).
struct AxisShift {
    bool shifted = false;     // the condition of Eq. 6 held
    Vec2 shift;               // Δx_sub [m]
    double turn = 0.0;        // Δθ_sub [rad]
    double pivot_rate = 0.0;  // ω_p after the step [rad/s]
    Vec2 pivot_arm;           // the centroid relative to the moved centre [m]
    double torque_ref = 0.0;  // T' of this step for the next step's sign test [N m]
};
// load: the flow's force and torque T' about the centre at the start of the step;
// omega_after: ω^(n+1) after friction; capacity: Σ f_k.
AxisShift axis_shift(const BodyParams& body, const BodyState& state, const std::vector<GroundPatch>& patches,
                     const FluidLoad& load, double omega_after, double capacity, const Inertia& eff, double dt);

}  // namespace flotsam::debris
