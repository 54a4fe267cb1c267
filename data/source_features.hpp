// Debris sources from a port's own GIS layers: a point layer (one body per feature) and a
// polygon layer (a yard filled with bodies), in any vector format GDAL reads, carried into
// the scene's CRS. This reads the features and their attributes; app/ turns them into
// bodies with the debris catalogue and debris/source_layout.hpp.
//
// Attributes (names case-insensitive; units as stated, docs/gis.md "Debris sources"):
//   type      text, required: a debris catalogue entry ("container_40ft", "car", ...)
//   heading   [degree] long axis from +x (east), counter-clockwise; or
//   bearing   [degree] long axis clockwise from north (heading = 90 - bearing)
//   mass      [kg], length, width, height [m]: override the catalogue entry (points and yards)
//   count     yards: how many bodies (spread over the widest gap that holds them)
//   gap       yards: clear distance between neighbours [m] (every place at that gap)
// A yard without a heading stacks along its outline's longest edge.
#pragma once
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "formats/scene.hpp"

namespace flotsam {

struct SourceFeature {
    std::string layer;   // the layer's name
    long long fid = 0;   // the feature's id in the layer
    std::string where;   // "file:layer feature N", for messages
    std::string type;    // catalogue entry
    double heading_deg = std::nan("");  // [degree] from +x, counter-clockwise; NaN: not given
    double mass = std::nan(""), length = std::nan(""), width = std::nan(""), height = std::nan("");  // NaN: the catalogue's
    int count = 0;                    // yards: 0 when not given
    double gap = std::nan("");        // yards [m]; NaN when not given
    bool is_yard = false;             // a polygon (rings) rather than a point (x, y)
    double x = 0.0, y = 0.0;          // a point, in the scene's CRS [m]
    std::vector<std::vector<std::array<double, 2>>> rings;  // a yard: outline, then holes [m]
};

// The features of `layers` of `path` (all its layers when empty), in layer then feature
// order. Errors name the file, layer and feature: a geometry that is neither a point nor
// a polygon (a multi-part one included), a missing or empty `type`, both heading and
// bearing, count or gap on a point, a count below 1 or a negative gap, non-finite or
// non-positive dimensions, no features at all.
std::vector<SourceFeature> read_source_features(const std::string& path, const std::vector<std::string>& layers,
                                               const Scene& scene);

}  // namespace flotsam
