#include "debris/body.hpp"

#include <cmath>
#include <utility>
#include <vector>

#include "common/error.hpp"
#include "debris/impacts.hpp"

namespace flotsam::debris {

BodyDef default_body_def() { return BodyDef{}; }

const Settings<BodyDef>& body_shape_settings() {
    static const Settings<BodyDef> table = {
        {"length", "m", "body length", Range::positive("m").up_to(1e4), &BodyDef::length},
        {"width", "m", "body width", Range::positive("m").up_to(1e4), &BodyDef::width},
        {"height", "m", "body height", Range::positive("m").up_to(1e4), &BodyDef::height},
        // Below 1: the model floats the body.
        {"specific-gravity", "1", "body specific gravity", Range::positive().below(1.0), &BodyDef::specific_gravity},
    };
    return table;
}

const Settings<BodyDef>& body_coefficient_settings() {
    static const Settings<BodyDef> table = {
        {"cd1", "1", "drag coefficient, flow toward a face", Range::closed(0.0, 100.0), &BodyDef::cd1},
        {"cd2", "1", "drag coefficient, flow leaving a face", Range::closed(0.0, 100.0), &BodyDef::cd2},
        {"cm", "1", "inertia coefficient Cm = 1 + Ca", Range::closed(1.0, 100.0), &BodyDef::cm},
        {"mu", "1", "friction coefficient with the ground (Fc)", Range::closed(0.0, 10.0), &BodyDef::mu},
        {"restitution", "1", "coefficient of restitution against obstacles", Range::closed(0.0, 1.0), &BodyDef::restitution},
    };
    return table;
}

const Settings<BodyDef>& body_model_settings() {
    static const Settings<BodyDef> table = {
        {"added-mass",
         "",
         "added mass: implicit (stable) or explicit (the stability study only)",
         {},
         choice_of<&BodyDef::added_mass>()},
        {"axis-shift", "", "local contact pivots about the contact centroid (paper Eqs. 6-10)", {}, &BodyDef::axis_shift},
        {"pivot-rate",
         "",
         "the axis shift's rotation rate from step to step: carried (the yaw equation about the contact), restarted from rest "
         "each step, or braked by the friction's moment (not in the paper)",
         {},
         choice_of<&BodyDef::pivot_rate>()},
        {"added-yaw-inertia",
         "",
         "yaw inertia with the added mass's share, rho Ca Vs (L^2 + B^2)/12 (false: the paper's m (L^2 + B^2)/12, Eq. 2)",
         {},
         &BodyDef::added_yaw_inertia},
        {"samples-per-face", "1", "drag sample points per side face", Range::count(1, max_samples_per_face),
         &BodyDef::samples_per_face},
        {"step-tolerance", "1", "ground above the bottom by more than this x draft blocks", Range::closed(0.0, 10.0),
         &BodyDef::step_tolerance},
        {"blocking-ground",
         "",
         "ground that blocks where it rises above the bottom by more than the step: land (above still water), any, or none",
         {},
         choice_of<&BodyDef::blocking_ground>()},
    };
    return table;
}

const Settings<BodyDef>& body_variant_settings() {
    static const Settings<BodyDef> table = {
        {"contact",
         "",
         "friction model: the whole bottom at the centre (CC) or local, cell by cell (LC)",
         {},
         choice_of<&BodyDef::contact>()},
        {"collision",
         "",
         "collision model: one contact per step (SC) or repeated until none (MC)",
         {},
         choice_of<&BodyDef::collision>()},
    };
    return table;
}

BodyParams make_body_params(const BodyDef& def, double water_density) {
    for (const auto* table : {&body_shape_settings(), &body_coefficient_settings(), &body_model_settings()})
        for (const auto& s : *table)
            if (s.is_number()) check_range(s.key, s.number(def), s.range, "body '" + def.name + "'");
    for (const auto& [name, value] : {std::pair<const char*, double>{"x", def.x}, {"y", def.y}, {"heading", def.heading}})
        check_range(name, value, Range::any(), "body '" + def.name + "'");
    BodyParams p;
    p.def = def;
    p.plan_area = def.length * def.width;
    p.mass = def.specific_gravity * water_density * p.plan_area * def.height;
    p.draft = p.mass / (water_density * p.plan_area);
    p.radius_sq = (def.length * def.length + def.width * def.width) / 12.0;
    p.inertia = p.mass * p.radius_sq;
    p.step_height = def.step_tolerance * p.draft;
    p.half_diagonal = 0.5 * std::hypot(def.length, def.width);
    p.impact_stiffness = def.impact_stiffness > 0.0 ? def.impact_stiffness : default_impact_stiffness(def.length);
    p.impact_threshold = impact_speed_threshold * std::sqrt(def.length / 0.25);
    p.impact_separation = impact_separation_lengths * def.length;
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
