// The colours and QGIS styles of what export/ writes: the maps' colour ramps, and the
// styles of the tracks, buildings, sources, the scene's features and the hazard regions.
#pragma once
#include <string>
#include <vector>

#include "export/qgis_style.hpp"

namespace flotsam::gis::styles {

// Colours (light to strong): depths in blues (sea paler than land), speeds and
// probabilities in warm colours, arrival from early (dark red) to late (blue).
extern const std::vector<std::string> sea_depth_colours, land_depth_colours, flow_speed_colours, arrival_colours,
    probability_colours, debris_speed_colours;

std::string tracks_qml(const std::vector<std::string>& sources);  // one colour per source
std::string buildings_qml();                                       // by hit probability, labelled by the p90 force
std::string buildings_force_qml();                                 // by the p90 force
// Debris sources in purple, labelled by `label` (a QGIS expression).
std::string sources_qml(bool points, const std::string& label);
extern const char* const source_label;  // "layer (type)"
// The scene's named features: gauges black, sections and regions (of the statistics) teal.
std::string feature_qml(qgis::Symbol::Kind kind);
std::string hazard_regions_qml();  // hatched by flow direction

}  // namespace flotsam::gis::styles
