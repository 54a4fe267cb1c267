#include "app/sourced_bodies.hpp"

#include <filesystem>
#include <numbers>

#include "common/checks.hpp"
#include "common/error.hpp"
#include "data/source_features.hpp"
#include "debris/catalogue.hpp"
#include "debris/scene_match.hpp"
#include "debris/source_layout.hpp"

namespace flotsam {

namespace {

constexpr double water_density = 1000.0;  // [kg/m³], as the catalogue's specific gravities

// The feature's body: the entry's shape and coefficients, the attributes over them.
debris::BodyDef body_of(const SourceFeature& f, const debris::BodyDef& model) {
    const debris::CatalogueBody* entry = debris::find_catalogue_body(f.type);
    if (!entry)
        fail(f.where, "attribute 'type' = '" + f.type + "'", "not in the debris catalogue (" + debris::catalogue_names() + ")");
    const debris::BodyDef c = debris::catalogue_body_def(f.type, f.where, water_density);
    debris::BodyDef b = model;
    b.length = std::isnan(f.length) ? c.length : f.length;
    b.width = std::isnan(f.width) ? c.width : f.width;
    b.height = std::isnan(f.height) ? c.height : f.height;
    const double mass = std::isnan(f.mass) ? entry->mass : f.mass;
    b.specific_gravity = mass / (water_density * b.length * b.width * b.height);
    if (!(b.specific_gravity < 1.0))
        fail(f.where, "mass " + number_text(mass) + " kg",
             "a " + number_text(b.length) + " x " + number_text(b.width) + " x " + number_text(b.height) +
                 " m box this heavy never floats (specific gravity " + number_text(b.specific_gravity) + ")");
    for (const auto& setting : debris::body_coefficient_settings()) setting.set_number(b, setting.number(c));
    b.impact_stiffness = c.impact_stiffness;
    return b;
}

// A yard is a simple polygon, and its layout is estimated before it is made: the places
// it tests at gap 0 (a 1e12 m² yard of containers is 3.5e10 of them) against the bound
// of a run (docs/reliability.md, "Every run is bounded") and the machine's memory.
void check_yard(const SourceFeature& f, const debris::Yard& yard, const debris::BodyDef& b, bool allow_large_run) {
    if (const auto c = debris::polygon_crossing(yard.rings))
        fail(f.where, "polygon",
             "crosses itself: the edge from (" + coordinate_text((*c)[0][0]) + ", " + coordinate_text((*c)[0][1]) +
                 ") crosses the edge from (" + coordinate_text((*c)[1][0]) + ", " + coordinate_text((*c)[1][1]) +
                 "); a yard is a simple polygon (QGIS's Fix geometries mends it)");
    const double places = debris::yard_lattice_places(yard, b.length, b.width);
    const std::string text = "a yard of " + number_text(debris::polygon_area(yard.rings)) + " m² for bodies of " +
                             number_text(b.length) + " x " + number_text(b.width) + " m";
    check_work("yard", text, places, max_yard_places, "places to lay out", allow_large_run, f.where);
    check_allocation("yard", text, places, 2.0 * sizeof(debris::Pose), "places", f.where);
}

}  // namespace

std::vector<SourcedBody> bodies_from_sources(const std::string& path, const std::vector<std::string>& layers,
                                             const Scene& scene, const debris::BodyDef& model, bool allow_large_run) {
    std::vector<SourcedBody> out;
    // On the scene's grid, off its buildings; the error names the feature (and its file).
    auto check_start = [&](const SourceFeature& f, const debris::BodyDef& b) {
        try {
            debris::check_body_start(b, scene.grid, "scene " + scene.path, &scene);
        } catch (const Error& e) {
            throw Error(f.where + ": " + e.what());
        }
    };
    for (const SourceFeature& f : read_source_features(path, layers, scene)) {
        const debris::BodyDef b = body_of(f, model);
        const std::string source = f.layer + "/" + std::to_string(f.fid);
        if (!f.is_yard) {
            SourcedBody s{b, source, f.type};
            s.def.name = source;
            s.def.x = f.x;
            s.def.y = f.y;
            s.def.heading = (std::isnan(f.heading_deg) ? 0.0 : f.heading_deg) * std::numbers::pi / 180.0;
            check_start(f, s.def);
            out.push_back(s);
            continue;
        }
        const debris::Yard yard{f.rings, f.heading_deg, f.gap, f.count};
        check_yard(f, yard, b, allow_large_run);
        const debris::YardLayout layout = debris::lay_out_yard(yard, b.length, b.width);
        if (layout.poses.empty() || (f.count > 0 && int(layout.poses.size()) < f.count))
            fail(f.where, "yard",
                 "a yard of " + number_text(debris::polygon_area(f.rings)) + " m² holds " + std::to_string(layout.poses.size()) +
                     " bodies of type " + f.type + " (" + number_text(b.length) + " x " + number_text(b.width) + " m) at gap " +
                     number_text(std::isnan(f.gap) ? 0.0 : f.gap) + " m, heading " + number_text(layout.heading_deg) +
                     " degrees" + (f.count > 0 ? "; count asks for " + std::to_string(f.count) : std::string()));
        for (std::size_t k = 0; k < layout.poses.size(); ++k) {
            SourcedBody s{b, source, f.type};
            s.def.name = source + "/" + std::to_string(k + 1);
            s.def.x = layout.poses[k].x;
            s.def.y = layout.poses[k].y;
            s.def.heading = layout.poses[k].heading;
            check_start(f, s.def);
            out.push_back(s);
        }
    }
    return out;
}

sweep::BodySpec body_spec_of(const SourcedBody& s) {
    sweep::BodySpec b;
    b.name = s.def.name;
    b.x = s.def.x;
    b.y = s.def.y;
    b.heading = s.def.heading;
    b.heading_deg = s.def.heading * 180.0 / std::numbers::pi;
    b.def = s.def;
    b.type = s.type;
    b.source = s.source;
    return b;
}

void expand_sources(sweep::SweepSpec& spec, const Scene* scene, bool allow_large_run) {
    if (spec.sources.empty()) return;
    if (!scene) fail(spec.path, "[[sources]]", "sources need a scene ([sweep] scene = \"...\" or --scene): its CRS places them");
    for (const sweep::SourceFileSpec& file : spec.sources) {
        if (!std::filesystem::exists(file.file))
            fail(spec.path, "line " + std::to_string(file.line) + ": [[sources]] file", "'" + file.file + "' does not exist");
        for (const SourcedBody& s : bodies_from_sources(file.file, file.layers, *scene, file.model, allow_large_run)) {
            for (const auto& other : spec.bodies)
                if (other.name == s.def.name)
                    fail(spec.path, "line " + std::to_string(file.line), "body name '" + s.def.name + "' used twice ([[body]] name = ...)");
            const sweep::BodySpec b = body_spec_of(s);
            spec.bodies.push_back(b);
        }
    }
    spec.sources.clear();
}

}  // namespace flotsam
