// A layer of a vector file (GeoPackage, shapefile, GeoJSON, ... anything GDAL reads)
// opened for reading into a scene: the layer found by name, and the transformation from
// its CRS to the scene's. Shared by the building footprints, the Manning polygons and
// the debris sources, so that all three refuse the same mismatches with the same words.
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "data/gdal_support.hpp"
#include "formats/scene.hpp"

namespace flotsam {

struct VectorLayer {
    gdal::Dataset file;
    OGRLayer* layer = nullptr;
    std::string where;  // "path" or "path:layer", for messages
    // From the layer's CRS to the scene's; null when they are the same (or both local).
    std::unique_ptr<OGRCoordinateTransformation> to_scene;
    std::string note;  // "reprojected from ... to the scene's ...", or ""

    // A feature's geometry in the scene's CRS (a copy); errors name the feature.
    std::unique_ptr<OGRGeometry> geometry_in_scene(const OGRFeature& feature) const;
    // The index of attribute `field`, or -1 when the layer has none of that name.
    int field_index(const std::string& field) const;
    // "a, b, c": the layer's attribute names, for messages.
    std::string field_names() const;
};

// Opens layer `layer_name` of `path` ("": the first layer). Errors name the file: a
// missing layer (listing those there are), no CRS where the scene has one or the
// reverse, a CRS that cannot be transformed to the scene's.
VectorLayer open_vector_layer(const std::string& path, const std::string& layer_name, const Scene& scene);

// The names of the layers of a vector file, in order.
std::vector<std::string> vector_layer_names(const std::string& path);

// The scene's CRS as GDAL's; nullopt for local metres.
std::optional<OGRSpatialReference> scene_spatial_ref(const Scene& s);

}  // namespace flotsam
