#include "debris/catalogue.hpp"

#include "common/error.hpp"

namespace flotsam::debris {

namespace {

// ISO 668:2013 (Series 1 freight containers): external dimensions of the 1CC (20 ft) and
// 1AAA/1AA (40 ft) containers, and the rated maximum gross mass of 30 480 kg for both.
// Tare masses: typical of steel dry-van containers (about 2 200-2 400 kg for 20 ft,
// 3 600-3 900 kg for 40 ft; a container's own figure is on its CSC plate).
constexpr double iso_20ft_length = 6.058, iso_40ft_length = 12.192, iso_width = 2.438, iso_height = 2.591;
constexpr double iso_max_gross = 30480.0;
const char* const iso_source =
    "ISO 668:2013 external dimensions and rated gross mass; tare typical of steel dry vans; box coefficients of Chida & "
    "Mori (drag, inertia) and friction of steel on concrete or asphalt (0.3-0.5, the paper's 0.4 taken)";

// Impact stiffness k (debris/impacts.hpp). Logs: FEMA P-646's 2.4e6 N/m (from measured
// log impacts, Haehnel & Daly). Containers: 85 kip/in (1.5e7 N/m), the longitudinal
// stiffness of a 20 ft container in full-scale impact tests (Piran Aghl, Naito, Riggs
// 2014) behind ASCE 7-16's container provisions; taken for the 40 ft and the laden ones
// too (assumed: the frame's rails crush, whatever the cargo). Car: from the energy of a
// 56 km/h full-width rigid-barrier test (NCAP) over about 0.6 m of crush, k = m v² / x²
// ≈ 1.0e6 N/m (derived, assumed). The paper's box: 2.4e6 N/m at full scale (the wood-log
// value; the box is wooden) and that / 250² in the flume (Froude: k scales as L²).
constexpr double log_stiffness = 2.4e6, container_stiffness = 1.5e7, car_stiffness = 1.0e6;
const char* const container_stiffness_source =
    "85 kip/in (1.5e7 N/m): longitudinal stiffness of a 20 ft container in full-scale impact tests (Piran Aghl et al. 2014) "
    "behind ASCE 7-16 Section 6.11's container provision; the same taken for 40 ft and laden containers (assumed)";

std::vector<CatalogueBody> make_catalogue() {
    std::vector<CatalogueBody> c;
    c.push_back({"paper_box", "the flume's debris model of Chida & Mori (1/250): a wooden box, specific gravity 0.25", 0.25, 0.10,
                 0.10, 0.625, 0.8, 0.4, 2.0, 0.4, 0.5,
                 "Chida & Mori: 0.25 x 0.10 x 0.10 m, s.g. 0.25, Cd1 0.8, Cd2 0.4, Cm 2.0, Fc 0.4 (the control case); "
                 "restitution 0.5 is flotsam's choice",
                 log_stiffness / (250.0 * 250.0),
                 "the full-scale box's 2.4e6 N/m / 250^2 (Froude: k scales as L^2); assumed"});
    c.push_back({"paper_box_full_scale", "the paper's box at the prototype scale (x250, Froude): 62.5 x 25 x 25 m, s.g. 0.25", 62.5,
                 25.0, 25.0, 0.25 * 1000.0 * 62.5 * 25.0 * 25.0, 0.8, 0.4, 2.0, 0.4, 0.5,
                 "paper_box scaled by the flume's 1/250: lengths x250, mass x250^3, coefficients unchanged", log_stiffness,
                 "FEMA P-646's wood-log stiffness, 2.4e6 N/m (the box is wooden); assumed"});
    c.push_back({"container_20ft", "empty 20 ft ISO container (1CC), tare 2 300 kg", iso_20ft_length, iso_width, iso_height, 2300.0,
                 0.8, 0.4, 2.0, 0.4, 0.5, iso_source,
                 container_stiffness, container_stiffness_source});
    c.push_back({"container_20ft_laden", "20 ft ISO container at its rated gross mass, 30 480 kg", iso_20ft_length, iso_width,
                 iso_height, iso_max_gross, 0.8, 0.4, 2.0, 0.4, 0.5, iso_source,
                 container_stiffness, container_stiffness_source});
    c.push_back({"container_40ft", "empty 40 ft ISO container (1AA), tare 3 750 kg", iso_40ft_length, iso_width, iso_height, 3750.0,
                 0.8, 0.4, 2.0, 0.4, 0.5, iso_source,
                 container_stiffness, container_stiffness_source});
    c.push_back({"container_40ft_laden", "40 ft ISO container at its rated gross mass, 30 480 kg", iso_40ft_length, iso_width,
                 iso_height, iso_max_gross, 0.8, 0.4, 2.0, 0.4, 0.5, iso_source,
                 container_stiffness, container_stiffness_source});
    c.push_back({"car", "mid-size passenger car, 4.5 x 1.8 x 1.5 m, kerb mass 1 400 kg", 4.5, 1.8, 1.5, 1400.0, 0.8, 0.4, 2.0, 0.5,
                 0.5,
                 "typical mid-size saloon (C/D segment) dimensions and kerb mass; as a water-tight box it floats at 0.17 m, "
                 "earlier than a real car (ground clearance, leaks; flood guidance: about 0.3 m floats many cars); tyre "
                 "friction on wet asphalt taken as 0.5 (assumed)",
                 car_stiffness, "m v^2 / x^2 of a 56 km/h full-width rigid-barrier test (NCAP) over about 0.6 m of crush; derived, assumed"});
    c.push_back({"fishing_vessel_small", "small fishing boat (under 5 GT, FRP), 10 x 2.8 x 1.2 m, 4 000 kg", 10.0, 2.8, 1.2, 4000.0,
                 0.8, 0.4, 2.0, 0.4, 0.5,
                 "typical of the small FRP coastal fishing boats in Japanese ports (length about 10 m); assumed values, "
                 "replace with the vessel's own; box drag overstates a hull's (no bow)",
                 log_stiffness, "FEMA P-646's wood-log stiffness for a wooden or FRP hull; assumed"});
    return c;
}

}  // namespace

const std::vector<CatalogueBody>& catalogue() {
    static const std::vector<CatalogueBody> c = make_catalogue();
    return c;
}

const CatalogueBody* find_catalogue_body(const std::string& name) {
    for (const auto& b : catalogue())
        if (b.name == name) return &b;
    return nullptr;
}

std::string catalogue_names() {
    std::string s;
    for (const auto& b : catalogue()) s += (s.empty() ? "" : ", ") + b.name;
    return s;
}

BodyDef catalogue_body_def(const std::string& name, const std::string& where, double water_density) {
    const CatalogueBody* c = find_catalogue_body(name);
    if (!c) fail(where, "body type '" + name + "'", "not in the catalogue (" + catalogue_names() + ")");
    BodyDef d = default_body_def();
    d.length = c->length;
    d.width = c->width;
    d.height = c->height;
    d.specific_gravity = c->mass / (water_density * c->length * c->width * c->height);
    d.cd1 = c->cd1;
    d.cd2 = c->cd2;
    d.cm = c->cm;
    d.mu = c->mu;
    d.restitution = c->restitution;
    d.impact_stiffness = c->impact_stiffness;
    return d;
}

}  // namespace flotsam::debris
