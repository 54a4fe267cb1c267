#include "debris/collision.hpp"

#include <algorithm>

#include "debris/kernels.hpp"

namespace flotsam::debris {

namespace {

// Moving out by exactly the depth leaves the body touching; this much more leaves it
// clear of the next detection, far below anything the output resolves [m].
constexpr double separation_slop = 1e-9;

Box pose(const BodyState& s, const BodyParams& b) { return Box::make({s.x, s.y}, s.theta, b.def.length, b.def.width); }

// The impulse at one contact (zero unless it approaches); whether it was applied.
bool apply_impulse(const ObstacleContact& c, const BodyParams& b, double mass, double inertia, BodyState& s) {
    const Vec2 r = c.point - Vec2{s.x, s.y};
    const Vec2 vp = Vec2{s.vx, s.vy} + spin(s.omega, r);
    const double j = contact_impulse(dot(vp, c.normal), b.def.restitution, mass, inertia, r, c.normal);
    if (!(j > 0.0)) return false;
    s.vx += j / mass * c.normal.x;
    s.vy += j / mass * c.normal.y;
    s.omega += j * cross(r, c.normal) / inertia;
    return true;
}

double deepest(const std::vector<ObstacleContact>& cs) {
    double d = 0.0;
    for (const auto& c : cs) d = std::max(d, c.depth);
    return d;
}

// The axis shift's rotation about x_sub as the centre's velocity and yaw rate.
void hand_pivot_to_centre(BodyState& s) {
    if (s.pivot_rate == 0.0) return;
    const Vec2 arm{-s.pivot_ax, -s.pivot_ay};  // the centre relative to the axis
    const Vec2 v = spin(s.pivot_rate, arm);
    s.vx += v.x;
    s.vy += v.y;
    s.omega += s.pivot_rate;
    s.pivot_rate = 0.0;
    s.pivot_ax = s.pivot_ay = 0.0;
}

}  // namespace

CollisionOutcome resolve_collisions(const ObstacleMap& obstacles, const BodyParams& body, CollisionModel model, double mass,
                                    double inertia, double bottom, int max_passes, const StepMove& move, BodyState& state,
                                    const Box& footprint, std::vector<ObstacleContact>& contacts) {
    const BlockingGround rule = body.def.blocking_ground;
    const auto detect = [&](const Box& box) {
        contacts.clear();
        obstacles.find_contacts(box, bottom, body.step_height, contacts, 1e-10, rule);
    };
    CollisionOutcome out;
    detect(footprint);
    if (contacts.empty()) return out;
    out.touched = true;
    hand_pivot_to_centre(state);
    auto by_depth = [](const ObstacleContact& a, const ObstacleContact& b) { return a.depth > b.depth; };

    if (model == CollisionModel::single) {
        const auto& c = *std::min_element(contacts.begin(), contacts.end(), by_depth);
        apply_impulse(c, body, mass, inertia, state);
        state.x += (c.depth + separation_slop) * c.normal.x;
        state.y += (c.depth + separation_slop) * c.normal.y;
        detect(pose(state, body));
        out.residual = deepest(contacts);
        return out;
    }

    // The pose the step reached and the velocities it reached it with: the pose is that
    // one plus the step's share of what the impulses changed (Euler: x^n + Δt V, the
    // corrected V; the axis shift's turn, done before, stays), plus the moves out.
    const BodyState reached = state;
    Vec2 moved_out;
    double turned_out = 0.0;
    const double w = move.new_weight * move.dt;
    for (; out.passes < max_passes && !contacts.empty(); ++out.passes) {
        std::sort(contacts.begin(), contacts.end(), by_depth);
        bool corrected = false;
        for (const auto& c : contacts) corrected = apply_impulse(c, body, mass, inertia, state) || corrected;
        if (!corrected) {
            // Nothing approaches, yet the body overlaps: move out of each contact by what
            // is left of its depth after this pass's earlier moves.
            const Vec2 centre{state.x, state.y};
            Vec2 dx;
            double dtheta = 0.0;
            for (const auto& c : contacts) {
                const Vec2 r = c.point - centre;
                const double left = c.depth - (dot(dx, c.normal) + dtheta * cross(r, c.normal));
                if (!(left > 0.0)) continue;
                const SeparatingMove m = separating_move(left + separation_slop, mass, inertia, r, c.normal);
                dx += m.shift;
                dtheta += m.turn;
            }
            moved_out += dx;
            turned_out += dtheta;
        }
        state.x = reached.x + w * (state.vx - reached.vx) + moved_out.x;
        state.y = reached.y + w * (state.vy - reached.vy) + moved_out.y;
        state.theta = reached.theta + w * (state.omega - reached.omega) + turned_out;
        detect(pose(state, body));
    }
    out.residual = deepest(contacts);
    out.unresolved = out.residual > move.tolerance;
    return out;
}

}  // namespace flotsam::debris
