// The flow's load on one body and the inertia it acts on (MODEL.md, "Hydrodynamic
// force"; docs/debris.md, "Forces"):
//
//   drag on each side face k, sampled at points p:  F = ½ ρ C_d A |u_n| u_n n_k,
//       u_n = (u(p) − v_body(p)) · n_k,  C_d = Cd1 where u_n < 0, Cd2 where u_n ≥ 0,
//       A = segment length × the wetted height at p: min(d, h(p)) afloat; resting on
//       the ground, from the body's bottom up to the water level there,
//       min(d, h(p) − (z_bot − z(p))), z(p) the ground at p;
//   inertia at the centre:                          F_I = ρ V_s Cm Du/Dt,
//   added mass on the left-hand side:               (m + ρ C_a V_s) dV/dt = F.
//
// The torque T' is Σ (p − x_g) × F over the face samples (no friction).
#pragma once
#include "debris/body.hpp"
#include "debris/box.hpp"
#include "debris/flow_sampler.hpp"
#include "debris/kernels.hpp"
#include "debris/obstacles.hpp"

namespace flotsam::debris {

// The body's pose and velocities as the fluid force sees them.
struct Motion {
    Vec2 centre;        // x_g [m]
    double theta;       // heading [rad]
    Vec2 velocity;      // V [m/s]
    double omega;       // ω about the centre [rad/s]
    double pivot_rate;  // ω_p about the contact centroid [rad/s]
    Vec2 pivot_arm;     // that centroid relative to the centre [m]
};

// Where the body's bottom is, for the wetted height of its faces: afloat (at η_c − d, the
// faces wetted to the draft where the water is that deep), or resting on ground higher
// than that (the highest ground under its footprint: MODEL.md, "Vertical position").
struct Resting {
    bool on_ground = false;               // the bottom rests on the ground
    double bottom = 0.0;                  // z_bot: η_c − d afloat, else the highest ground under the footprint [m]
    const ObstacleMap* ground = nullptr;  // the ground's elevation z(p) (on_ground)
};

// The flow's force on the body without friction [N] and its torque T' about the centre
// [N m].
struct FluidLoad {
    Vec2 force;
    double torque = 0.0;
};

// The load at time t (in the reader's prepared interval). centre: the flow sampled at
// the centre (for Du/Dt); submerged: V_s = L B min(d, h_c) [m³]; rho: ρw [kg/m³].
FluidLoad fluid_load(const FlowSampler& flow, const BodyParams& body, const Motion& motion, const FlowPointAccel& centre,
                     double submerged, double t, double rho, const Resting& rest = {});
// The same, given the footprint at the motion's pose (Box::make of its centre and heading).
FluidLoad fluid_load(const FlowSampler& flow, const BodyParams& body, const Motion& motion, const Box& box,
                     const FlowPointAccel& centre, double submerged, double t, double rho, const Resting& rest = {});

// Effective mass and yaw inertia: the body plus, when implicit, the added mass ρ C_a V_s
// [kg]. The yaw inertia is the paper's (Eq. 2, I = m (L² + B²)/12) unless the body asks
// for the added yaw inertia, ρ C_a V_s (L² + B²)/12 in the same ratio as the added mass
// [kg m²].
struct Inertia {
    double mass, inertia, added_mass;
};
Inertia effective_inertia(const BodyParams& body, double submerged_volume, double rho);

}  // namespace flotsam::debris
