#include "debris/dynamics.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "debris/box.hpp"
#include "debris/collision.hpp"
#include "debris/kernels.hpp"

namespace flotsam::debris {

StepDef default_step_def() { return StepDef{}; }

namespace {

// A velocity below this has no direction (a point that does not slide) [m/s].
constexpr double sliding_epsilon = 1e-12;

// Effective mass and yaw inertia: the body plus, when implicit, the added mass ρ C_a V_s
// and an added yaw inertia in the same ratio (ρ C_a V_s (L² + B²)/12) [kg], [kg m²].
struct Inertia {
    double mass, inertia, added_mass;
};
Inertia effective_inertia(const BodyParams& b, double submerged_volume, double rho) {
    const double added = rho * (b.def.cm - 1.0) * submerged_volume;
    if (b.def.added_mass == AddedMass::explicit_) return {b.mass, b.inertia, added};
    return {b.mass + added, b.inertia + added * b.radius_sq, added};
}

// The body's bottom elevation [m]: at η − d while the centre is deeper than the draft,
// else on the ground of the centre cell.
double bottom_elevation(const ObstacleMap& obstacles, double x, double y, double depth, double draft) {
    return obstacles.ground(x, y) + std::max(depth - draft, 0.0);
}

// The body's pose and velocities as the fluid force sees them.
struct Motion {
    Vec2 centre;        // x_g [m]
    double theta;       // heading [rad]
    Vec2 velocity;      // V [m/s]
    double omega;       // ω about the centre [rad/s]
    double pivot_rate;  // ω_p about the contact centroid [rad/s]
    Vec2 pivot_arm;     // that centroid relative to the centre [m]
};

// The flow's force on the body without friction: inertia ρ V_s Cm Du/Dt at the centre
// plus the face-sampled drag, and the drag's torque T' about the centre [N], [N m].
struct FluidLoad {
    Vec2 force;
    double torque = 0.0;
};
FluidLoad fluid_load(const StepContext& ctx, const BodyParams& b, const Motion& m, const FlowPointAccel& centre, double submerged,
                     double t) {
    const BodyDef& def = b.def;
    const double rho = ctx.def.water_density;
    const Box box = Box::make(m.centre, m.theta, def.length, def.width);
    // Velocity of the body point at r from the centre: translation, rotation about the
    // centre, and rotation about the pivot while the axis is shifted.
    auto point_velocity = [&](Vec2 r) { return m.velocity + spin(m.omega, r) + spin(m.pivot_rate, r - m.pivot_arm); };
    FluidLoad load;
    load.force =
        (rho * submerged * def.cm) * Vec2{centre.du_dt, centre.dv_dt};  // Froude-Krylov + added-mass part of the fluid acceleration
    const int ns = def.samples_per_face;
    for (int face = 0; face < 4; ++face) {
        const bool long_normal = face < 2;  // faces across the long axis (length B) have normal ±axis_long
        const double sign = (face % 2 == 0) ? 1.0 : -1.0;
        const Vec2 n = sign * (long_normal ? box.axis_long : box.axis_wide);
        const Vec2 tangent = long_normal ? box.axis_wide : box.axis_long;
        const double offset = long_normal ? box.half_length : box.half_width;
        const double face_length = long_normal ? def.width : def.length;
        const double segment = face_length / ns;
        for (int q = 0; q < ns; ++q) {
            const Vec2 r = offset * n + ((q + 0.5) / ns - 0.5) * face_length * tangent;
            const FlowPoint fp = ctx.flow.sample(m.centre.x + r.x, m.centre.y + r.y, t);
            const double wetted = std::min(b.draft, fp.depth);
            if (wetted <= 0.0) continue;
            const Vec2 u_rel = Vec2{fp.u, fp.v} - point_velocity(r);
            const Vec2 dF = face_drag(u_rel, n, segment * wetted, def.cd1, def.cd2, rho);
            load.force += dF;
            load.torque += cross(r, dF);
        }
    }
    return load;
}

}  // namespace

double step_body(const StepContext& ctx, const BodyParams& b, BodyState& s, BodyStats& stats, double dt, StepScratch& scratch) {
    const BodyDef& def = b.def;
    const double rho = ctx.def.water_density, g = ctx.def.gravity, t = s.time;
    const Vec2 xg{s.x, s.y};
    const FlowPointAccel centre = ctx.flow.sample_accel(xg.x, xg.y, t);
    ++stats.steps;
    if (!(s.flags & flag_released)) {
        if (centre.depth > b.draft) {
            s.flags |= flag_released;
        } else {
            s.time = t + dt;
            return 0.0;
        }
    }
    const double bottom = bottom_elevation(ctx.obstacles, xg.x, xg.y, centre.depth, b.draft);
    const double submerged = b.plan_area * std::min(b.draft, centre.depth);
    const Inertia eff = effective_inertia(b, submerged, rho);
    const Box box = Box::make(xg, s.theta, def.length, def.width);
    const Vec2 V{s.vx, s.vy};
    const Motion now{xg, s.theta, V, s.omega, s.pivot_rate, Vec2{s.pivot_ax, s.pivot_ay}};

    // ---- hydrodynamic force F and its torque T' about the centre (no friction) ----
    const FluidLoad load = fluid_load(ctx, b, now, centre, submerged, t);
    Vec2 F = load.force;
    double T = load.torque;
    Vec2 explicit_force;  // −ρ C_a V_s dV/dt with last step's dV/dt (unstable: for the study only)
    double explicit_torque = 0.0;
    if (def.added_mass == AddedMass::explicit_) {
        explicit_force = (-eff.added_mass) * Vec2{s.ax_prev, s.ay_prev};
        explicit_torque = -eff.added_mass * b.radius_sq * s.alpha_prev;
        F += explicit_force;
        T += explicit_torque;
    }
    // Velocities first (added mass on the left), then positions. Euler: the acceleration
    // at the start of the step. Heun: its mean with the acceleration at the Euler-predicted
    // end (pose, velocities and time t + dt; the pivot motion held as it is). The axis
    // shift below uses the force at the start of the step in both.
    Vec2 V_trial = V + (dt / eff.mass) * F;
    double omega_trial = s.omega + dt / eff.inertia * T;
    if (ctx.def.integrator == Integrator::heun) {
        Motion end = now;
        end.velocity = V_trial;
        end.omega = omega_trial;
        end.centre = xg + dt * V_trial;
        end.theta = s.theta + dt * omega_trial;
        const FlowPointAccel centre_end = ctx.flow.sample_accel(end.centre.x, end.centre.y, t + dt);
        const double submerged_end = b.plan_area * std::min(b.draft, centre_end.depth);
        const Inertia eff_end = effective_inertia(b, submerged_end, rho);
        const FluidLoad load_end = fluid_load(ctx, b, end, centre_end, submerged_end, t + dt);
        V_trial = V + (0.5 * dt) * ((1.0 / eff.mass) * F + (1.0 / eff_end.mass) * (load_end.force + explicit_force));
        omega_trial = s.omega + 0.5 * dt * (T / eff.inertia + (load_end.torque + explicit_torque) / eff_end.inertia);
    }

    // ---- friction patches ----
    auto& patches = scratch.patches;
    patches.clear();
    if (def.contact == ContactModel::center) {
        if (centre.depth < b.draft)
            patches.push_back({Vec2{}, b.plan_area, friction_capacity(def.mu, 1.0, b.mass, rho, b.plan_area, centre.depth, g)});
    } else {
        const CellWindow cells =
            ctx.flow.cells_for(xg.x - box.extent_x(), xg.x + box.extent_x(), xg.y - box.extent_y(), xg.y + box.extent_y());
        if (ctx.flow.min_depth(cells) < b.draft) {  // else no point under the body can be shallower than the draft
            scratch.footprint.clear();
            footprint_patches(box, ctx.obstacles.grid(), scratch.footprint);
            for (const auto& fp : scratch.footprint) {
                const double h = ctx.flow.depth(fp.centroid.x, fp.centroid.y, t);
                if (h < b.draft)
                    patches.push_back({fp.centroid - xg, fp.area,
                                       friction_capacity(def.mu, fp.area / b.plan_area, b.mass, rho, b.plan_area, h, g)});
            }
        }
    }
    double capacity = 0.0;
    Vec2 V_new = V_trial;
    double omega_new = omega_trial;
    if (!patches.empty()) {
        // Each patch resists the sliding of its own point. Translation first, with the
        // sliding at the trial velocities; then the torque, with the sliding at the new
        // translation, so that a body friction has stopped is not turned by it (a static
        // corner does not drive a rotation; a dragging one does). Neither reverses the
        // motion within the step: a component that would change sign stops instead, which
        // is also the static case (at rest with the driving force below the capacity, the
        // trial velocity is reversed, so the body stays).
        Vec2 Ff;
        for (const auto& p : patches) {
            capacity += p.capacity;
            Ff += (-p.capacity) * unit_or_zero(V_trial + spin(omega_trial, p.r), sliding_epsilon);
        }
        V_new = V_trial + (dt / eff.mass) * Ff;
        if (dot(V_new, V_trial) <= 0.0) V_new = Vec2{};
        double Tf = 0.0;
        for (const auto& p : patches)
            Tf += cross(p.r, (-p.capacity) * unit_or_zero(V_new + spin(omega_trial, p.r), sliding_epsilon));
        omega_new = omega_trial + dt / eff.inertia * Tf;
        if (omega_new * omega_trial <= 0.0) omega_new = 0.0;
    }

    // ---- axis shift (LC): rotate about the contact centroid (paper Eqs. 6-10) ----
    // T' in the condition T'^n T'^(n+1) ≥ 0 is taken about the axis in use: the centre,
    // or the contact centroid while the axis is shifted (choice: about the centre, T' of
    // a body held at one corner in a uniform current is near zero and flips sign with
    // round-off, which would end every pivot after a few steps).
    Vec2 shift;
    double turn = 0.0, pivot_rate = 0.0, torque_ref = T;
    bool shifted = false;
    Vec2 pivot_arm_new;
    if (def.contact == ContactModel::local && def.axis_shift && !patches.empty()) {
        Vec2 r_sub;  // contact-area centroid relative to the centre
        double area = 0.0;
        for (const auto& p : patches) {
            r_sub += p.area * p.r;
            area += p.area;
        }
        r_sub = (1.0 / area) * r_sub;
        const Vec2 arm = -1.0 * r_sub;                // centre relative to the axis
        const double torque_sub = T + cross(arm, F);  // flow force moved to the axis
        const double torque_now = (s.flags & flag_pivoting) ? torque_sub : T;
        if (norm(arm) > 1e-9 && s.omega * omega_new <= 0.0 && s.torque_prev * torque_now >= 0.0 && norm(F) <= capacity) {
            shifted = true;
            torque_ref = torque_sub;
            const double inertia_sub = eff.inertia + eff.mass * dot(arm, arm);  // parallel axis
            double friction_torque = 0.0;
            for (const auto& p : patches) friction_torque += p.capacity * norm(p.r - r_sub);
            double w = s.pivot_rate + dt / inertia_sub * torque_sub;
            const double brake = dt / inertia_sub * friction_torque;  // never reverses the pivot
            w = std::fabs(w) <= brake ? 0.0 : w - std::copysign(brake, w);
            pivot_rate = w;
            turn = w * dt;
            shift = r_sub + rotate(arm, turn);    // x_g* − x_g^n = (x_sub − x_g^n) + R (x_g^n − x_sub)
            pivot_arm_new = rotate(r_sub, turn);  // the axis stays put; seen from the moved centre
            if (w != 0.0) ++stats.axis_shifts;
        }
    }
    if (def.added_mass == AddedMass::explicit_) {
        s.ax_prev = (V_new.x - V.x) / dt;
        s.ay_prev = (V_new.y - V.y) / dt;
        s.alpha_prev = (omega_new - s.omega) / dt;
    }
    s.torque_prev = torque_ref;
    s.vx = V_new.x;
    s.vy = V_new.y;
    s.omega = omega_new;
    s.pivot_rate = pivot_rate;
    s.pivot_ax = pivot_rate != 0.0 ? pivot_arm_new.x : 0.0;
    s.pivot_ay = pivot_rate != 0.0 ? pivot_arm_new.y : 0.0;
    // Heun moves with the mean of the old and new velocities (second order), Euler with
    // the new one (semi-implicit: a body friction has stopped does not move).
    const double w_new = ctx.def.integrator == Integrator::heun ? 0.5 : 1.0;
    const Vec2 V_move = w_new * V_new + (1.0 - w_new) * V;
    const double omega_move = w_new * omega_new + (1.0 - w_new) * now.omega;
    s.x += dt * V_move.x + shift.x;
    s.y += dt * V_move.y + shift.y;
    s.theta += dt * omega_move + turn;

    const auto before = box.corners();
    const auto after = Box::make({s.x, s.y}, s.theta, def.length, def.width).corners();
    double travel = 0.0;
    for (int k = 0; k < 4; ++k) travel = std::max(travel, norm(after[k] - before[k]));

    std::uint8_t flags = s.flags & (flag_released | flag_colliding);
    if (!patches.empty()) flags |= flag_grounded;
    if (shifted) flags |= flag_pivoting;
    if (norm(V_new) > 0.0 || omega_new != 0.0 || pivot_rate != 0.0) flags |= flag_moving;

    // ---- obstacles ----
    const CollisionOutcome hit = resolve_collisions(ctx.obstacles, b, def.collision, eff.mass, eff.inertia, bottom,
                                                    ctx.def.max_collision_passes, s, scratch.contacts);
    if (hit.touched) {
        flags |= flag_colliding;
        ++stats.collisions;
        stats.unresolved += hit.unresolved ? 1 : 0;
        stats.max_residual_overlap = std::max(stats.max_residual_overlap, hit.residual);
    }
    s.flags = flags;
    s.time = t + dt;
    return travel;
}

double stable_step(const StepContext& ctx, const BodyParams& b, const BodyState& s) {
    const double half_diagonal = 0.5 * std::hypot(b.def.length, b.def.width);
    // Fastest corner: |V| + |ω| r for rotation about the centre; a pivot about a point
    // inside the footprint moves a corner at most |ω_sub| × 2 r.
    const double vertex_speed = std::hypot(s.vx, s.vy) + (std::fabs(s.omega) + 2.0 * std::fabs(s.pivot_rate)) * half_diagonal;
    const Grid& g = ctx.obstacles.grid();
    const double reach = ctx.def.vertex_step_fraction * std::min(g.dx, g.dy);
    return vertex_speed * ctx.def.dt_max > reach ? reach / vertex_speed : ctx.def.dt_max;
}

double window_pad(const StepContext& ctx, const BodyParams& b) {
    const Grid& g = ctx.obstacles.grid();
    const double reach = ctx.def.vertex_step_fraction * std::min(g.dx, g.dy);
    return 0.5 * std::hypot(b.def.length, b.def.width) + 2.0 * reach + 2.0 * std::max(g.dx, g.dy);
}

bool advance_body(const StepContext& ctx, const BodyParams& b, BodyState& s, BodyStats& stats, double t_end, StepScratch& scratch) {
    const Grid& g = ctx.obstacles.grid();
    const double reach = ctx.def.vertex_step_fraction * std::min(g.dx, g.dy);
    const double pad = window_pad(ctx, b);
    while (s.time < t_end) {
        double dt = std::min(stable_step(ctx, b, s), t_end - s.time);
        if (t_end - s.time - dt < 1e-9 * ctx.def.dt_max) dt = t_end - s.time;  // no sliver steps
        const CellWindow need = ctx.flow.cells_for(s.x - pad, s.x + pad, s.y - pad, s.y + pad);
        if (!ctx.flow.window().contains(need)) return false;
        // The limit is set from the velocity at the start of the step; if the flow
        // accelerates the body so that a corner moves more than twice that within the step,
        // redo it shorter (tunnelling through a one-cell wall needs a whole cell).
        const BodyState saved = s;
        const BodyStats saved_stats = stats;
        for (int attempt = 0;; ++attempt) {
            const double travel = step_body(ctx, b, s, stats, dt, scratch);
            if (travel <= 2.0 * reach || attempt >= 20) break;
            s = saved;
            stats = saved_stats;
            dt *= 0.5;
        }
        if (s.time > t_end || t_end - s.time < 1e-12) s.time = t_end;
    }
    return true;
}

}  // namespace flotsam::debris
