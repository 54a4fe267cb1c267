#include "debris/body.hpp"

#include <cmath>

#include "common/error.hpp"

namespace flotsam::debris {

BodyDef default_body_def() { return BodyDef{}; }

BodyParams make_body_params(const BodyDef& def, double water_density) {
    auto positive = [&](double v, const char* what) {
        if (!(v > 0.0) || !std::isfinite(v)) fail("body '" + def.name + "'", what, "must be positive, got " + std::to_string(v));
    };
    positive(def.length, "length");
    positive(def.width, "width");
    positive(def.height, "height");
    positive(def.specific_gravity, "specific gravity");
    if (def.specific_gravity >= 1.0)
        fail("body '" + def.name + "'", "specific gravity", "must be below 1 (the model floats the body)");
    if (def.cd1 < 0 || def.cd2 < 0) fail("body '" + def.name + "'", "drag coefficients", "must not be negative");
    if (def.cm < 1.0) fail("body '" + def.name + "'", "cm", "must be at least 1 (Cm = 1 + C_a)");
    if (def.mu < 0) fail("body '" + def.name + "'", "mu", "must not be negative");
    if (def.restitution < 0 || def.restitution > 1) fail("body '" + def.name + "'", "restitution", "must be in [0, 1]");
    if (def.samples_per_face < 1 || def.samples_per_face > 16) fail("body '" + def.name + "'", "samples per face", "must be 1..16");
    BodyParams p;
    p.def = def;
    p.plan_area = def.length * def.width;
    p.mass = def.specific_gravity * water_density * p.plan_area * def.height;
    p.draft = p.mass / (water_density * p.plan_area);
    p.radius_sq = (def.length * def.length + def.width * def.width) / 12.0;
    p.inertia = p.mass * p.radius_sq;
    p.step_height = def.step_tolerance * p.draft;
    return p;
}

BodyState initial_state(const BodyDef& def, double time) {
    BodyState s;
    s.x = def.x;
    s.y = def.y;
    s.theta = def.heading;
    s.time = time;
    return s;
}

}  // namespace flotsam::debris
