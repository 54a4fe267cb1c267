#include "debris/collision.hpp"

#include <algorithm>

#include "debris/kernels.hpp"

namespace flotsam::debris {

namespace {

// Moving out by exactly the depth leaves the body touching; this much more leaves it
// clear of the next detection, far below anything the output resolves [m].
constexpr double separation_slop = 1e-9;

Box pose(const BodyState& s, const BodyParams& b) { return Box::make({s.x, s.y}, s.theta, b.def.length, b.def.width); }

void apply_impulse(const ObstacleContact& c, const BodyParams& b, double mass, double inertia, BodyState& s) {
    const Vec2 r = c.point - Vec2{s.x, s.y};
    const Vec2 vp = Vec2{s.vx, s.vy} + spin(s.omega, r);
    const double j = contact_impulse(dot(vp, c.normal), b.def.restitution, mass, inertia, r, c.normal);
    s.vx += j / mass * c.normal.x;
    s.vy += j / mass * c.normal.y;
    s.omega += j * cross(r, c.normal) / inertia;
}

double deepest(const std::vector<ObstacleContact>& cs) {
    double d = 0.0;
    for (const auto& c : cs) d = std::max(d, c.depth);
    return d;
}

}  // namespace

CollisionOutcome resolve_collisions(const ObstacleMap& obstacles, const BodyParams& body, CollisionModel model, double mass,
                                    double inertia, double bottom, int max_passes, BodyState& state, const Box& footprint,
                                    std::vector<ObstacleContact>& contacts) {
    CollisionOutcome out;
    contacts.clear();
    obstacles.find_contacts(footprint, bottom, body.step_height, contacts);
    if (contacts.empty()) return out;
    out.touched = true;
    state.pivot_rate = 0.0;
    auto by_depth = [](const ObstacleContact& a, const ObstacleContact& b) { return a.depth > b.depth; };

    if (model == CollisionModel::single) {
        const auto& c = *std::min_element(contacts.begin(), contacts.end(), by_depth);
        apply_impulse(c, body, mass, inertia, state);
        state.x += (c.depth + separation_slop) * c.normal.x;
        state.y += (c.depth + separation_slop) * c.normal.y;
        contacts.clear();
        obstacles.find_contacts(pose(state, body), bottom, body.step_height, contacts);
        out.residual = deepest(contacts);
        return out;
    }

    for (int pass = 0; pass < max_passes && !contacts.empty(); ++pass) {
        std::sort(contacts.begin(), contacts.end(), by_depth);
        Vec2 moved;  // correction applied so far in this pass
        for (const auto& c : contacts) {
            apply_impulse(c, body, mass, inertia, state);
            const double left = c.depth - dot(moved, c.normal);
            if (left > 0.0) {
                const Vec2 shift = (left + separation_slop) * c.normal;
                state.x += shift.x;
                state.y += shift.y;
                moved += shift;
            }
        }
        contacts.clear();
        obstacles.find_contacts(pose(state, body), bottom, body.step_height, contacts);
    }
    out.residual = deepest(contacts);
    out.unresolved = !contacts.empty();
    return out;
}

}  // namespace flotsam::debris
