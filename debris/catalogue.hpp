// The debris catalogue: named bodies with their dimensions, mass and coefficients, and
// where those numbers come from (docs/debris.md has the table and the reasoning). Used
// by name in `flotsam debris --body NAME` and in sweep specs ([[body]] type = "NAME").
// The body model is a box, so each entry is the box that floats and drags like the
// object: its outer dimensions and its real mass.
#pragma once
#include <string>
#include <vector>

#include "debris/body.hpp"

namespace flotsam::debris {

struct CatalogueBody {
    std::string name;          // the key users type, e.g. "container_40ft"
    std::string description;   // one line
    double length = 0.0;       // L [m]
    double width = 0.0;        // B [m]
    double height = 0.0;       // D [m]
    double mass = 0.0;         // [kg]
    double cd1 = 0.8;          // drag coefficient, flow toward a face [-]
    double cd2 = 0.4;          // drag coefficient, flow leaving a face [-]
    double cm = 2.0;           // inertia coefficient [-]
    double mu = 0.4;           // friction coefficient with the ground [-]
    double restitution = 0.5;  // against obstacles [-]
    std::string source;        // where the numbers come from
    double impact_stiffness = 0.0;  // k of the impact-force estimate (debris/impacts.hpp) [N/m]
    std::string stiffness_source;   // where k comes from
};

// All entries, in a fixed order.
const std::vector<CatalogueBody>& catalogue();

// The entry called `name`, or nullptr.
const CatalogueBody* find_catalogue_body(const std::string& name);

// A body definition from the entry called `name`: its dimensions, its specific gravity
// m / (ρw L B D), its coefficients and impact stiffness; the rest (contact and collision models, samples,
// step tolerance) as in default_body_def(). Errors name `where` and list the known names.
BodyDef catalogue_body_def(const std::string& name, const std::string& where, double water_density = 1000.0);

// "name1, name2, ..." for messages and --help.
std::string catalogue_names();

}  // namespace flotsam::debris
