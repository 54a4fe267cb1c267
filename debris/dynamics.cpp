#include "debris/dynamics.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "debris/box.hpp"
#include "debris/collision.hpp"
#include "debris/kernels.hpp"
#include "debris/loads.hpp"

namespace flotsam::debris {

StepDef default_step_def() { return StepDef{}; }

namespace {

// A cell the body reaches into by less than this many cells is not under it: an overlap
// the collisions leave as resolved (up to unresolved_overlap_cells) is a wall being
// pushed out of, not ground to rest on; were it ground, a body pressed against a step
// too high for it would rest on the step's edge and be carried onto it [-].
constexpr double footprint_overlap_cells = 2.0 * unresolved_overlap_cells;

// What a step starts from: the flow at the centre and what follows from it.
struct StepStart {
    FlowPointAccel centre;  // the flow at x_g
    double submerged;       // V_s = L B min(d, h_c) [m³]
    Inertia eff;            // effective mass and yaw inertia
    Box box;                // the pose
    Motion now;             // pose and velocities
    Resting rest;           // where its bottom is (resting_place, once the contact patches are known)
};

StepStart step_start(const StepContext& ctx, const BodyParams& b, const BodyState& s, const FlowPointAccel& centre) {
    const Vec2 xg{s.x, s.y};
    const double submerged = b.plan_area * std::min(b.draft, centre.depth);
    return StepStart{centre,
                     submerged,
                     effective_inertia(b, submerged, ctx.def.water_density),
                     Box::make(xg, s.theta, b.def.length, b.def.width),
                     Motion{xg, s.theta, Vec2{s.vx, s.vy}, s.omega, s.pivot_rate, Vec2{s.pivot_ax, s.pivot_ay}},
                     {}};
}

// The water over the obstacle grid's cells at one time: the flow's depth at their centres.
class WaterOverCells final : public CellWater {
public:
    WaterOverCells(const FlowSampler& flow, const Grid& cells, double t) : flow_(flow), cells_(cells), at_(flow.at_time(t)) {}
    double depth(int i, int j) const override { return flow_.depth(cells_.x(i), cells_.y(j), at_); }

private:
    const FlowSampler& flow_;
    const Grid& cells_;
    FlowSampler::TimeStencil at_;
};

// Loads: the flow's force and torque T' at the start of the step (the explicit added
// mass −ρ C_a V_s a^(n−1) included where chosen: unstable, for the study only), and the
// trial velocities they give with the added mass on the left. Euler: the acceleration at
// the start of the step. Heun: its mean with the acceleration at the Euler-predicted end
// (pose, velocities and time t + dt; the pivot motion held as it is). The axis shift uses
// the force at the start of the step in both.
struct Loads {
    FluidLoad load;
    Velocities trial;
};

Loads integrate_loads(const StepContext& ctx, const BodyParams& b, const BodyState& s, const StepStart& st, double dt) {
    const double rho = ctx.def.water_density, t = s.time;
    const Inertia& eff = st.eff;
    Loads out;
    out.load = fluid_load(ctx.flow, b, st.now, st.box, st.centre, st.submerged, t, rho, st.rest);
    Vec2 explicit_force;
    double explicit_torque = 0.0;
    if (b.def.added_mass == AddedMass::explicit_) {
        explicit_force = (-eff.added_mass) * Vec2{s.ax_prev, s.ay_prev};
        if (b.def.added_yaw_inertia) explicit_torque = -eff.added_mass * b.radius_sq * s.alpha_prev;
        out.load.force += explicit_force;
        out.load.torque += explicit_torque;
    }
    const Vec2 F = out.load.force;
    const double T = out.load.torque;
    out.trial.V = st.now.velocity + (dt / eff.mass) * F;
    out.trial.omega = s.omega + dt / eff.inertia * T;
    if (ctx.def.integrator == Integrator::heun) {
        Motion end = st.now;
        end.velocity = out.trial.V;
        end.omega = out.trial.omega;
        end.centre = st.now.centre + dt * out.trial.V;
        end.theta = s.theta + dt * out.trial.omega;
        const FlowPointAccel centre_end = ctx.flow.sample_accel(end.centre.x, end.centre.y, t + dt);
        const double submerged_end = b.plan_area * std::min(b.draft, centre_end.depth);
        const Inertia eff_end = effective_inertia(b, submerged_end, rho);
        const FluidLoad load_end = fluid_load(ctx.flow, b, end, centre_end, submerged_end, t + dt, rho, st.rest);
        out.trial.V =
            st.now.velocity + (0.5 * dt) * ((1.0 / eff.mass) * F + (1.0 / eff_end.mass) * (load_end.force + explicit_force));
        out.trial.omega = s.omega + 0.5 * dt * (T / eff.inertia + (load_end.torque + explicit_torque) / eff_end.inertia);
    }
    return out;
}

// Commit: the new velocities, pose (Eq. 10: x^(n+1) = x^n + Δx_g + Δx_sub) and flags.
// Heun moves with the mean of the old and new velocities (second order), Euler with the
// new one (semi-implicit: a body friction has stopped does not move). Returns the largest
// displacement of a corner [m]; `pose` is the footprint at the new pose.
double commit(const StepContext& ctx, const BodyParams& b, BodyState& s, const StepStart& st, const Velocities& next,
              const AxisShift& a, bool grounded, double dt, Box& pose) {
    if (b.def.added_mass == AddedMass::explicit_) {
        s.ax_prev = (next.V.x - st.now.velocity.x) / dt;
        s.ay_prev = (next.V.y - st.now.velocity.y) / dt;
        s.alpha_prev = (next.omega - st.now.omega) / dt;
    }
    s.torque_prev = a.torque_ref;
    s.vx = next.V.x;
    s.vy = next.V.y;
    s.omega = next.omega;
    s.pivot_rate = a.pivot_rate;
    s.pivot_ax = a.pivot_rate != 0.0 ? a.pivot_arm.x : 0.0;
    s.pivot_ay = a.pivot_rate != 0.0 ? a.pivot_arm.y : 0.0;
    const double w_new = ctx.def.integrator == Integrator::heun ? 0.5 : 1.0;
    const Vec2 V_move = w_new * next.V + (1.0 - w_new) * st.now.velocity;
    const double omega_move = w_new * next.omega + (1.0 - w_new) * st.now.omega;
    s.x += dt * V_move.x + a.shift.x;
    s.y += dt * V_move.y + a.shift.y;
    s.theta += dt * omega_move + a.turn;

    const auto before = st.box.corners();
    pose = Box::make({s.x, s.y}, s.theta, b.def.length, b.def.width);
    const auto after = pose.corners();
    double travel = 0.0;
    for (int k = 0; k < 4; ++k) travel = std::max(travel, norm(after[k] - before[k]));

    std::uint8_t flags = s.flags & (flag_released | flag_colliding);
    if (grounded) flags |= flag_grounded;
    if (a.shifted) flags |= flag_pivoting;
    if (norm(next.V) > 0.0 || next.omega != 0.0 || a.pivot_rate != 0.0) flags |= flag_moving;
    s.flags = flags;
    return travel;
}

// The contact episodes with buildings after a step (debris/impacts.hpp): a building
// touched with no episode open opens one, an impact where the approach was fast enough;
// an open episode whose building is neither touched nor within the separation of the
// body's pose after the step ends.
void track_impacts(const StepContext& ctx, const BodyParams& b, const BodyState& s, double t, StepScratch& scratch,
                   BodyImpacts& impacts) {
    if (scratch.touches.empty() && impacts.open.empty()) return;
    const auto is_open = [&](std::int32_t id) {
        return std::find(impacts.open.begin(), impacts.open.end(), id) != impacts.open.end();
    };
    const auto touched = [&](std::int32_t id) {
        return std::any_of(scratch.touches.begin(), scratch.touches.end(),
                           [&](const BuildingTouch& k) { return k.building == id; });
    };
    // Open episodes that this step did not touch: still near (within the separation)?
    if (std::any_of(impacts.open.begin(), impacts.open.end(), [&](std::int32_t id) { return !touched(id); })) {
        Box near = Box::make({s.x, s.y}, s.theta, b.def.length, b.def.width);
        near.half_length += b.impact_separation;
        near.half_width += b.impact_separation;
        std::vector<ObstacleCollision>& found = scratch.contacts;
        found.clear();
        ctx.obstacles.find_contacts(near, 1e30, 0.0, found, 0.0, BlockingGround::none);  // only buildings block at that bottom
        std::erase_if(impacts.open, [&](std::int32_t id) {
            return !touched(id) &&
                   std::none_of(found.begin(), found.end(), [&](const ObstacleCollision& c) { return c.building == id; });
        });
    }
    for (const BuildingTouch& k : scratch.touches) {
        if (is_open(k.building)) continue;
        impacts.open.push_back(k.building);
        if (!(k.speed > b.impact_threshold)) continue;
        impacts.events.push_back(
            {t, 0, k.building, k.point.x, k.point.y, k.speed, impact_force(k.speed, b.mass, b.impact_stiffness), b.mass});
    }
}

// Collisions with the obstacles at the committed pose (SC or MC, debris/collision.hpp),
// for the bottom where the body rested at the start of the step. Ground blocks where it
// can (BlockingGround), rises more than the step height above that bottom, and the water
// over its cell is shallower than the draft (docs/debris.md, "Ground and obstacles"); so
// the ground under the footprint is never a wall, and land the body floats over neither.
void collide(const StepContext& ctx, const BodyParams& b, BodyState& s, BodyStats& stats, const StepStart& start, const Box& pose,
             double dt, StepScratch& scratch, BodyImpacts* impacts, bool defer_impacts) {
    const WaterOverCells water(ctx.flow, ctx.obstacles.grid(), s.time);
    const Blocking blocking{start.rest.bottom, b.step_height, b.def.blocking_ground, &water, b.draft};
    const Grid& g = ctx.obstacles.grid();
    const CollisionSetup setup{
        ctx.obstacles,
        blocking,
        b,
        start.eff.mass,
        start.eff.inertia,
        ctx.def.max_collision_passes,
        {dt, ctx.def.integrator == Integrator::heun ? 0.5 : 1.0, unresolved_overlap_cells * std::min(g.dx, g.dy)}};
    scratch.touches.clear();
    const CollisionOutcome hit = resolve_collisions(setup, s, pose, scratch.contacts, impacts ? &scratch.touches : nullptr);
    if (impacts && !defer_impacts) track_impacts(ctx, b, s, s.time + dt, scratch, *impacts);
    if (!hit.touched) return;
    s.flags |= flag_colliding;
    ++stats.collisions;
    double residual = hit.residual;
    bool unresolved = hit.unresolved;
    // Jammed: the passes could not clear the overlap (contacts on opposite sides whose
    // first-order moves out contradict each other, a body wedged across a gap narrower
    // than its projected width among the cells of a jagged bank). The body goes back to
    // where the step began, if that pose is clearer, and keeps its velocity along the
    // walls it was pressed against: walls are frictionless, so only the approach into them
    // is taken away (and the turn that jammed it).
    if (unresolved && b.def.collision == CollisionModel::multi) {
        scratch.jammed_at = scratch.contacts;  // the overlaps left
        const double at_start = deepest_overlap(ctx.obstacles, blocking, start.box, scratch.contacts);
        if (at_start < residual) {
            s.x = start.now.centre.x;
            s.y = start.now.centre.y;
            s.theta = start.now.theta;
            Vec2 v{s.vx, s.vy};
            for (int sweep = 0; sweep < 2; ++sweep)
                for (const ObstacleCollision& c : scratch.jammed_at)
                    if (const double vn = dot(v, c.normal); vn < 0.0) v = v - vn * c.normal;
            s.vx = v.x;
            s.vy = v.y;
            s.omega = s.pivot_rate = 0.0;
            residual = at_start;
            unresolved = at_start > setup.move.tolerance;
            ++stats.jams;
        }
    }
    stats.unresolved += unresolved ? 1 : 0;
    stats.max_residual_overlap = std::max(stats.max_residual_overlap, residual);
}

}  // namespace

Resting resting_place(const StepContext& ctx, const BodyParams& b, const Box& box, double centre_depth,
                      const std::vector<GroundPatch>& patches) {
    const double afloat = ctx.obstacles.ground(box.centre.x, box.centre.y) + centre_depth - b.draft;
    // The ground is looked at where some of it under the body may be above where it would
    // float: a contact patch, or any ground within reach above that. So no cell under the
    // footprint is ever above the bottom, and none of them can block the body.
    const bool maybe = (b.def.contact == ContactModel::local && !patches.empty()) ||
                       ctx.obstacles.ground_above(box, afloat, BlockingGround::any);
    const Grid& g = ctx.obstacles.grid();
    const double highest = maybe ? ctx.obstacles.highest_ground(box, footprint_overlap_cells * std::min(g.dx, g.dy)) : afloat;
    if (!(highest > afloat)) return Resting{false, afloat, nullptr};
    return Resting{true, highest, &ctx.obstacles};
}

namespace {

// What a step leaves for the contacts between bodies: how far a corner went, the
// effective inertia it was taken with and the bottom that decided what blocks.
struct StepOutcome {
    double travel = 0.0;  // [m]
    Inertia eff{};
    double bottom = 0.0;  // [m]
};

StepOutcome take_step(const StepContext& ctx, const BodyParams& b, BodyState& s, BodyStats& stats, double dt, StepScratch& scratch,
                      BodyImpacts* impacts, bool defer_impacts) {
    const double t = s.time, x0 = s.x, y0 = s.y;
    const FlowPointAccel centre = ctx.flow.sample_accel(s.x, s.y, t);
    ++stats.steps;
    StepStart st = step_start(ctx, b, s, centre);
    if (!(s.flags & flag_released)) {
        if (!(centre.depth > b.draft)) {  // a body starts once the depth at its centre exceeds the draft
            s.time = t + dt;
            // Until then it rests where it would rest released (no patches yet): that bottom
            // is what blocks it when another body pushes it (from the level less the draft,
            // the land under its own footprint walled it in).
            return {0.0, st.eff, resting_place(ctx, b, st.box, centre.depth, {}).bottom};
        }
        s.flags |= flag_released;
    }
    // A body grounded at its last step most likely is again: the depth bound is not tried.
    ground_patches(ctx.flow, ctx.obstacles.grid(), b, st.box, centre.depth, t, ctx.def.water_density, ctx.def.gravity,
                   scratch.footprint, scratch.patches, !(s.flags & flag_grounded));
    st.rest = resting_place(ctx, b, st.box, centre.depth, scratch.patches);
    const Loads loads = integrate_loads(ctx, b, s, st, dt);
    const Friction friction = apply_friction(scratch.patches, loads.trial, st.eff, dt);
    const AxisShift shift = axis_shift(b, s, scratch.patches, loads.load, friction.after.omega, friction.capacity, st.eff, dt);
    if (shift.shifted && shift.pivot_rate != 0.0) ++stats.axis_shifts;
    Box pose;
    const double travel = commit(ctx, b, s, st, friction.after, shift, !scratch.patches.empty(), dt, pose);
    collide(ctx, b, s, stats, st, pose, dt, scratch, impacts, defer_impacts);
    s.centre_vx = (s.x - x0) / dt;
    s.centre_vy = (s.y - y0) / dt;
    s.time = t + dt;
    return {travel, st.eff, st.rest.bottom};
}

// The step the vertex-speed limit allows a corner that may move `reach` [m] (≤ dt_max).
double vertex_step(const StepContext& ctx, const BodyParams& b, const BodyState& s, double reach) {
    // Fastest corner: |V| + |ω| r for rotation about the centre; a pivot about a point
    // inside the footprint moves a corner at most |ω_sub| × 2 r.
    const double vertex_speed = std::hypot(s.vx, s.vy) + (std::fabs(s.omega) + 2.0 * std::fabs(s.pivot_rate)) * b.half_diagonal;
    return vertex_speed * ctx.def.dt_max > reach ? reach / vertex_speed : ctx.def.dt_max;
}

double cell_reach(const StepContext& ctx) {
    const Grid& g = ctx.obstacles.grid();
    return ctx.def.vertex_step_fraction * std::min(g.dx, g.dy);
}

}  // namespace

double step_body(const StepContext& ctx, const BodyParams& b, BodyState& s, BodyStats& stats, double dt, StepScratch& scratch,
                 BodyImpacts* impacts) {
    return take_step(ctx, b, s, stats, dt, scratch, impacts, false).travel;
}

double stable_step(const StepContext& ctx, const BodyParams& b, const BodyState& s) {
    return vertex_step(ctx, b, s, cell_reach(ctx));
}

double window_pad(const StepContext& ctx, const BodyParams& b) {
    const Grid& g = ctx.obstacles.grid();
    const double reach = ctx.def.vertex_step_fraction * std::min(g.dx, g.dy);
    return b.half_diagonal + 2.0 * reach + 2.0 * std::max(g.dx, g.dy);
}

bool advance_body(const StepContext& ctx, const BodyParams& b, BodyState& s, BodyStats& stats, double t_end, StepScratch& scratch,
                  BodyImpacts* impacts) {
    const Grid& g = ctx.obstacles.grid();
    const double reach = ctx.def.vertex_step_fraction * std::min(g.dx, g.dy);
    const double pad = window_pad(ctx, b);
    while (s.time < t_end) {
        double dt = std::min(stable_step(ctx, b, s), t_end - s.time);
        if (t_end - s.time - dt < 1e-9 * ctx.def.dt_max) dt = t_end - s.time;  // no sliver steps
        const CellWindow need = ctx.flow.cells_for(s.x - pad, s.x + pad, s.y - pad, s.y + pad);
        if (!ctx.flow.covers(need)) return false;
        // The limit is set from the velocity at the start of the step; if the flow
        // accelerates the body so that a corner moves more than twice that within the step,
        // redo it shorter (tunnelling through a one-cell wall needs a whole cell).
        const BodyState saved = s;
        const BodyStats saved_stats = stats;
        // A step that is redone records nothing: its impacts and episodes are undone too.
        const std::size_t saved_events = impacts ? impacts->events.size() : 0;
        if (impacts) scratch.open_saved = impacts->open;
        for (int attempt = 0;; ++attempt) {
            const double travel = step_body(ctx, b, s, stats, dt, scratch, impacts);
            if (travel <= 2.0 * reach || attempt >= 20) break;
            s = saved;
            stats = saved_stats;
            if (impacts) {
                impacts->events.resize(saved_events);
                impacts->open = scratch.open_saved;
            }
            dt *= 0.5;
        }
        if (s.time > t_end || t_end - s.time < 1e-12) s.time = t_end;
    }
    return true;
}

namespace {

// The group's next step (≤ t_end − t), or 0 where a body would need flow outside the
// loaded window.
double group_step(const StepContext& ctx, const BodyGroup& group, double reach, double t, double t_end) {
    double dt = t_end - t;
    for (const int m : group.members) {
        const BodyState& s = group.states[std::size_t(m)];
        dt = std::min(dt, vertex_step(ctx, group.params[std::size_t(m)], s, reach));
        const double pad = window_pad(ctx, group.params[std::size_t(m)]);
        if (!ctx.flow.covers(ctx.flow.cells_for(s.x - pad, s.x + pad, s.y - pad, s.y + pad))) return 0.0;
    }
    if (t_end - t - dt < 1e-9 * ctx.def.dt_max) dt = t_end - t;  // no sliver steps
    return dt;
}

// What a step that is redone must undo: the bodies' states, counts and impacts.
void save_group(const BodyGroup& group, GroupScratch& gs) {
    for (std::size_t k = 0; k < group.members.size(); ++k) {
        const std::size_t m = std::size_t(group.members[k]);
        gs.saved[k] = group.states[m];
        gs.saved_stats[k] = group.stats[m];
        if (group.impacts) {
            gs.saved_events[k] = (*group.impacts)[m].events.size();
            gs.saved_open[k] = (*group.impacts)[m].open;
        }
    }
}

void restore_group(BodyGroup& group, const GroupScratch& gs) {
    for (std::size_t k = 0; k < group.members.size(); ++k) {
        const std::size_t m = std::size_t(group.members[k]);
        group.states[m] = gs.saved[k];
        group.stats[m] = gs.saved_stats[k];
        if (group.impacts) {
            (*group.impacts)[m].events.resize(gs.saved_events[k]);
            (*group.impacts)[m].open = gs.saved_open[k];
        }
    }
}

// Each body's own step of dt (its impacts held back for after the contacts between the
// bodies); the whole group redone shorter where a corner moved more than twice what the
// step was set for (as advance_body). Returns the step taken.
double step_each(const StepContext& ctx, BodyGroup& group, double dt, double reach, GroupScratch& gs) {
    for (int attempt = 0;; ++attempt) {
        double travel = 0.0;
        for (std::size_t k = 0; k < group.members.size(); ++k) {
            const std::size_t m = std::size_t(group.members[k]);
            const StepOutcome o = take_step(ctx, group.params[m], group.states[m], group.stats[m], dt, gs.step,
                                            group.impacts ? &(*group.impacts)[m] : nullptr, true);
            GroupBody& gb = gs.bodies[k];
            gb.state = &group.states[m];
            gb.body = &group.params[m];
            gb.mass = o.eff.mass;
            gb.inertia = o.eff.inertia;
            gb.blocking.bottom = o.bottom;
            gb.touches = gs.step.touches;
            travel = std::max(travel, o.travel);
        }
        if (travel <= 2.0 * reach || attempt >= 20) return dt;
        restore_group(group, gs);
        dt *= 0.5;
    }
}

// After the contacts between the bodies: each one's counts, its centre's velocity over the
// step, and its impacts on buildings (its own step's touches and those of the contacts).
void account_group(const StepContext& ctx, BodyGroup& group, double t, double dt, bool met, double tolerance, GroupScratch& gs) {
    for (std::size_t k = 0; k < group.members.size(); ++k) {
        const std::size_t m = std::size_t(group.members[k]);
        const GroupBody& gb = gs.bodies[k];
        BodyState& s = group.states[m];
        BodyStats& st = group.stats[m];
        if (met && gb.met) {
            s.flags |= flag_released | flag_colliding;
            ++st.body_contacts;
            st.max_body_overlap = std::max(st.max_body_overlap, gb.body_overlap);
            st.max_residual_overlap = std::max(st.max_residual_overlap, gb.wall_overlap);
            const bool left = std::max(gb.body_overlap, gb.wall_overlap) > tolerance;
            if (left && st.unresolved == gs.saved_stats[k].unresolved) ++st.unresolved;
            s.centre_vx = (s.x - gs.saved[k].x) / dt;
            s.centre_vy = (s.y - gs.saved[k].y) / dt;
        }
        if (group.impacts) {
            gs.step.touches = gb.touches;
            track_impacts(ctx, group.params[m], s, t + dt, gs.step, (*group.impacts)[m]);
        }
    }
}

}  // namespace

bool advance_group(const StepContext& ctx, BodyGroup& group, double t_end, GroupScratch& gs) {
    const std::size_t n = group.members.size();
    const Grid& g = ctx.obstacles.grid();
    double narrowest = 1e300;
    for (const int m : group.members) narrowest = std::min(narrowest, group.params[std::size_t(m)].def.width);
    const double reach = ctx.def.vertex_step_fraction * std::min({g.dx, g.dy, narrowest});
    gs.bodies.resize(n);
    gs.saved.resize(n);
    gs.saved_stats.resize(n);
    gs.saved_events.resize(n);
    gs.saved_open.resize(n);
    BodyCollisionDef def{ctx.def.max_collision_passes,
                         {0.0, ctx.def.integrator == Integrator::heun ? 0.5 : 1.0, unresolved_overlap_cells * std::min(g.dx, g.dy)},
                         group.impacts != nullptr};
    for (;;) {
        const double t = group.states[std::size_t(group.members.front())].time;
        if (!(t < t_end)) return true;
        const double step = group_step(ctx, group, reach, t, t_end);
        if (step == 0.0) return false;
        save_group(group, gs);
        def.move.dt = step_each(ctx, group, step, reach, gs);
        // The contacts between the bodies, with what blocks each at the time the step
        // started (the water over the cells).
        const WaterOverCells water(ctx.flow, g, t);
        for (std::size_t k = 0; k < n; ++k) {
            const BodyParams& b = *gs.bodies[k].body;
            gs.bodies[k].blocking = Blocking{gs.bodies[k].blocking.bottom, b.step_height, b.def.blocking_ground, &water, b.draft};
        }
        const bool met = ctx.def.body_contact && n > 1 && resolve_body_collisions(ctx.obstacles, gs.bodies, def, gs.contacts);
        account_group(ctx, group, t, def.move.dt, met, def.move.tolerance, gs);
    }
}

}  // namespace flotsam::debris
