#include "export/styles.hpp"

namespace flotsam::gis::styles {

const std::vector<std::string> sea_depth_colours = {"#eff3ff", "#c6dbef", "#9ecae1", "#6baed6", "#3182bd"};
const std::vector<std::string> land_depth_colours = {"#c7e9f8", "#6cc3ef", "#1f8fd6", "#1750a8", "#2a0f78"};
const std::vector<std::string> flow_speed_colours = {"#fcfdbf", "#feb078", "#f1605d", "#b5367a", "#641a80"};
const std::vector<std::string> arrival_colours = {"#67001f", "#d6604d", "#fddbc7", "#d1e5f0", "#4393c3"};
const std::vector<std::string> probability_colours = {"#ffffb2", "#fed976", "#feb24c", "#fd8d3c", "#f03b20", "#bd0026"};
const std::vector<std::string> debris_speed_colours = {"#0d0887", "#7e03a8", "#cc4778", "#f89540", "#f0f921"};

namespace {

// Distinct colours for categories (matplotlib's "tab10"), repeated beyond ten.
const std::vector<std::string> category_colours = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                                   "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};

qgis::Symbol fill(const std::string& colour, const std::string& outline, double width_mm, double opacity = 1.0) {
    return {qgis::Symbol::Kind::fill, colour, outline, width_mm, 2.0, opacity, false};
}

}  // namespace

std::string tracks_qml(const std::vector<std::string>& sources) {
    qgis::VectorStyle s;
    s.field = "source";
    for (std::size_t k = 0; k < sources.size(); ++k)
        s.categories.push_back({sources[k],
                                sources[k],
                                {qgis::Symbol::Kind::line, category_colours[k % category_colours.size()], "", 0.15, 2.0, 0.3}});
    s.other = {qgis::Symbol::Kind::line, "#404040", "", 0.15, 2.0, 0.3};
    if (sources.empty()) s.symbol = s.other;
    return qgis::vector_qml(s);
}

std::string buildings_qml() {
    qgis::VectorStyle s;
    s.field = "hit_probability";
    s.classes.push_back({0.0, 0.0, "not hit", fill("#dcdcdc", "#a0a0a0", 0.1)});
    const qgis::RasterStyle p = qgis::probability_classes(probability_colours);
    double lower = 0.0;
    for (const qgis::ColourStop& c : p.stops) {
        s.classes.push_back({lower, c.value, "hit by " + c.label + " of the tracks", fill(c.colour, "#5a5a5a", 0.15)});
        lower = c.value;
    }
    // The force on the buildings that matter (hit by at least 5 % of the tracks): labels on
    // every hit building would cover the map.
    s.labels.expression =
        "CASE WHEN \"hit_probability\" >= 0.05 AND \"force_p90_N\" IS NOT NULL "
        "THEN 'p90 ' || format_number(\"force_p90_N\" / 1000, 0) || ' kN' END";
    s.labels.size_pt = 7;
    return qgis::vector_qml(s);
}

std::string buildings_force_qml() {
    qgis::VectorStyle s;
    s.field = "coalesce(\"force_p90_N\", -1)";
    s.classes = {{-1.0, -1.0, "not hit", fill("#dcdcdc", "#a0a0a0", 0.1)},
                 {0.0, 1e4, "p90 force ≤ 10 kN", fill("#fee5d9", "#5a5a5a", 0.15)},
                 {1e4, 1e5, "10 – 100 kN", fill("#fcae91", "#5a5a5a", 0.15)},
                 {1e5, 1e6, "100 kN – 1 MN", fill("#fb6a4a", "#5a5a5a", 0.15)},
                 {1e6, 1e15, "> 1 MN", fill("#cb181d", "#5a5a5a", 0.15)}};
    return qgis::vector_qml(s);
}

std::string sources_qml(bool points, const std::string& label) {
    qgis::VectorStyle s;
    s.symbol =
        points ? qgis::Symbol{qgis::Symbol::Kind::marker, "#7a0177", "#ffffff", 0.3, 2.6, 1.0, false} : fill("", "#7a0177", 0.7);
    s.labels.expression = label;
    s.labels.size_pt = 8;
    s.labels.colour = "#4a0048";
    s.labels.polygon_inside = !points;
    return qgis::vector_qml(s);
}
const char* const source_label = "\"layer\" || coalesce(' (' || \"type\" || ')', '')";

std::string feature_qml(qgis::Symbol::Kind kind) {
    qgis::VectorStyle s;
    s.symbol = kind == qgis::Symbol::Kind::marker ? qgis::Symbol{kind, "#202020", "#ffffff", 0.3, 2.0, 1.0, false}
               : kind == qgis::Symbol::Kind::line ? qgis::Symbol{kind, "#00747a", "", 0.6, 2.0, 1.0, false}
                                                  : fill("", "#00747a", 0.5);
    s.labels.expression = "\"name\"";
    s.labels.size_pt = 7;
    s.labels.colour = kind == qgis::Symbol::Kind::marker ? "#202020" : "#00474b";
    s.labels.polygon_inside = kind == qgis::Symbol::Kind::fill;
    return qgis::vector_qml(s);
}

std::string hazard_regions_qml() {
    qgis::VectorStyle s;
    s.field = "flow";
    s.categories = {
        {"inflow", "within ±22.5° of the inflow", {qgis::Symbol::Kind::fill, "#d7301f", "#d7301f", 0.5, 2.0, 0.8, true}},
        {"return flow", "within ±22.5° of the return flow", {qgis::Symbol::Kind::fill, "#f08c00", "#f08c00", 0.5, 2.0, 0.8, true}}};
    s.other = fill("", "#808080", 0.4);
    s.labels.expression = "\"source\"";
    s.labels.size_pt = 7;
    s.labels.colour = "#8a1c0f";
    return qgis::vector_qml(s);
}

}  // namespace flotsam::gis::styles
