#include "debris/loads.hpp"

#include <algorithm>

#include "debris/box.hpp"

namespace flotsam::debris {

Inertia effective_inertia(const BodyParams& b, double submerged_volume, double rho) {
    const double added = rho * (b.def.cm - 1.0) * submerged_volume;
    if (b.def.added_mass == AddedMass::explicit_) return {b.mass, b.inertia, added};
    const double added_yaw = b.def.added_yaw_inertia ? added * b.radius_sq : 0.0;
    return {b.mass + added, b.inertia + added_yaw, added};
}

FluidLoad fluid_load(const FlowSampler& flow, const BodyParams& b, const Motion& m, const FlowPointAccel& centre, double submerged,
                     double t, double rho, const Resting& rest) {
    return fluid_load(flow, b, m, Box::make(m.centre, m.theta, b.def.length, b.def.width), centre, submerged, t, rho, rest);
}

FluidLoad fluid_load(const FlowSampler& flow, const BodyParams& b, const Motion& m, const Box& box, const FlowPointAccel& centre,
                     double submerged, double t, double rho, const Resting& rest) {
    const BodyDef& def = b.def;
    // Velocity of the body point at r from the centre: translation, rotation about the
    // centre, and rotation about the pivot while the axis is shifted.
    auto point_velocity = [&](Vec2 r) { return m.velocity + spin(m.omega, r) + spin(m.pivot_rate, r - m.pivot_arm); };
    FluidLoad load;
    load.force =
        (rho * submerged * def.cm) * Vec2{centre.du_dt, centre.dv_dt};  // Froude-Krylov + added-mass part of the fluid acceleration
    const int ns = def.samples_per_face;
    double along[max_samples_per_face];  // sample q's place along a face, from its middle, in face lengths [-]
    for (int q = 0; q < ns; ++q) along[q] = (q + 0.5) / ns - 0.5;
    // The sample points of all faces first, sampled together; then their drag in turn.
    Vec2 normal[4];                       // outward unit normal of each face
    double segment[4];                    // length of a face's segment [m]
    Vec2 r_at[4 * max_samples_per_face];  // sample point relative to the centre [m]
    Vec2 p_at[4 * max_samples_per_face];  // sample point [m]
    for (int face = 0, k = 0; face < 4; ++face) {
        const bool long_normal = face < 2;  // faces across the long axis (length B) have normal ±axis_long
        const double sign = (face % 2 == 0) ? 1.0 : -1.0;
        normal[face] = sign * (long_normal ? box.axis_long : box.axis_wide);
        const Vec2 tangent = long_normal ? box.axis_wide : box.axis_long;
        const double offset = long_normal ? box.half_length : box.half_width;
        const double face_length = long_normal ? def.width : def.length;
        segment[face] = face_length / ns;
        for (int q = 0; q < ns; ++q, ++k) {
            r_at[k] = offset * normal[face] + along[q] * face_length * tangent;
            p_at[k] = Vec2{m.centre.x + r_at[k].x, m.centre.y + r_at[k].y};
        }
    }
    FlowPoint flow_at[4 * max_samples_per_face];
    flow.sample(p_at, 4 * ns, flow.at_time(t), flow_at);
    for (int k = 0; k < 4 * ns; ++k) {
        const int face = k / ns;
        // Resting on ground higher than where p's own ground is, the face starts that much
        // above p's ground: wetted from the bottom up to the water level at p.
        const double raised = rest.on_ground ? std::max(0.0, rest.bottom - rest.ground->ground(p_at[k].x, p_at[k].y)) : 0.0;
        const double wetted = std::min(b.draft, flow_at[k].depth - raised);
        if (wetted <= 0.0) continue;
        const Vec2 r = r_at[k];
        const Vec2 u_rel = Vec2{flow_at[k].u, flow_at[k].v} - point_velocity(r);
        const Vec2 dF = face_drag(u_rel, normal[face], segment[face] * wetted, def.cd1, def.cd2, rho);
        load.force += dF;
        load.torque += cross(r, dF);
    }
    return load;
}

}  // namespace flotsam::debris
