#include "debris/body.hpp"

#include <cmath>
#include <utility>
#include <vector>

#include "common/error.hpp"

namespace flotsam::debris {

const char* to_string(ContactModel m) { return m == ContactModel::center ? "center" : "local"; }
const char* to_string(CollisionModel m) { return m == CollisionModel::single ? "single" : "multi"; }
const char* to_string(AddedMass m) { return m == AddedMass::implicit ? "implicit" : "explicit"; }

ContactModel parse_contact_model(const std::string& s) {
    if (s == "center" || s == "centre" || s == "CC") return ContactModel::center;
    if (s == "local" || s == "LC") return ContactModel::local;
    fail("--contact", s, "expected 'center' or 'local'");
}
CollisionModel parse_collision_model(const std::string& s) {
    if (s == "single" || s == "SC") return CollisionModel::single;
    if (s == "multi" || s == "MC") return CollisionModel::multi;
    fail("--collision", s, "expected 'single' or 'multi'");
}
AddedMass parse_added_mass(const std::string& s) {
    if (s == "implicit") return AddedMass::implicit;
    if (s == "explicit") return AddedMass::explicit_;
    fail("--added-mass", s, "expected 'implicit' or 'explicit'");
}

BodyDef default_body_def() { return BodyDef{}; }

const Range& body_parameter_range(const std::string& name) {
    static const std::vector<std::pair<std::string, Range>> table = {
        {"length", Range::positive("m").up_to(1e4)},
        {"width", Range::positive("m").up_to(1e4)},
        {"height", Range::positive("m").up_to(1e4)},
        {"specific_gravity", Range::positive().below(1.0)},  // the model floats the body
        {"cd1", Range::closed(0.0, 100.0)},
        {"cd2", Range::closed(0.0, 100.0)},
        {"cm", Range::closed(1.0, 100.0)},  // Cm = 1 + C_a
        {"mu", Range::closed(0.0, 10.0)},
        {"restitution", Range::closed(0.0, 1.0)},
        {"samples_per_face", Range::count(1, 16)},
        {"step_tolerance", Range::closed(0.0, 10.0)},
    };
    for (const auto& [n, r] : table)
        if (n == name) return r;
    fail("", "body parameter '" + name + "'", "unknown");
}

BodyParams make_body_params(const BodyDef& def, double water_density) {
    const std::string body = "body '" + def.name + "'";
    const std::pair<const char*, double> values[] = {{"length", def.length},
                                                     {"width", def.width},
                                                     {"height", def.height},
                                                     {"specific_gravity", def.specific_gravity},
                                                     {"cd1", def.cd1},
                                                     {"cd2", def.cd2},
                                                     {"cm", def.cm},
                                                     {"mu", def.mu},
                                                     {"restitution", def.restitution},
                                                     {"samples_per_face", double(def.samples_per_face)},
                                                     {"step_tolerance", def.step_tolerance}};
    for (const auto& [name, value] : values) check_range(body + ": " + name, value, body_parameter_range(name));
    for (const auto& [name, value] : {std::pair<const char*, double>{"x", def.x}, {"y", def.y}, {"heading", def.heading}})
        check_range(body + ": " + name, value, Range::any());
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
