#include "data/vector_layer.hpp"

#include "common/error.hpp"

namespace flotsam {

std::optional<OGRSpatialReference> scene_spatial_ref(const Scene& s) {
    if (s.crs.empty()) return std::nullopt;
    return gdal::spatial_ref(s.crs, s.path.empty() ? std::string("scene") : s.path);
}

std::vector<std::string> vector_layer_names(const std::string& path) {
    gdal::Dataset ds = gdal::open_vector(path);
    std::vector<std::string> names;
    for (int k = 0; k < ds->GetLayerCount(); ++k) names.emplace_back(ds->GetLayer(k)->GetName());
    return names;
}

VectorLayer open_vector_layer(const std::string& path, const std::string& layer_name, const Scene& scene) {
    VectorLayer v;
    v.file = gdal::open_vector(path);
    GDALDataset& ds = *v.file;
    v.layer = layer_name.empty() ? (ds.GetLayerCount() > 0 ? ds.GetLayer(0) : nullptr) : ds.GetLayerByName(layer_name.c_str());
    if (!v.layer) {
        std::string names;
        for (int k = 0; k < ds.GetLayerCount(); ++k) names += (k ? ", " : "") + std::string(ds.GetLayer(k)->GetName());
        fail(path, layer_name.empty() ? "layers" : "layer '" + layer_name + "'",
             names.empty() ? "none in the file" : "not found (layers: " + names + ")");
    }
    v.where = path + (layer_name.empty() ? "" : ":" + layer_name);
    const OGRSpatialReference* layer_crs = gdal::layer_crs(*v.layer);
    const auto scene_crs = scene_spatial_ref(scene);
    if (scene_crs && !layer_crs)
        fail(v.where, "coordinate reference system",
             "none, while the scene is in " + gdal::label(*scene_crs) + ": assign the layer's CRS (e.g. ogr2ogr -a_srs EPSG:n)");
    if (!scene_crs && layer_crs)
        fail(v.where, "coordinate reference system " + gdal::label(*layer_crs),
             "the scene is in local metres (no CRS), so map coordinates cannot be placed in it: import the DEM with its CRS "
             "(--crs) first");
    if (scene_crs && layer_crs) {
        OGRSpatialReference from = *layer_crs;
        from.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        if (!from.IsSame(&*scene_crs)) {
            v.to_scene.reset(OGRCreateCoordinateTransformation(&from, &*scene_crs));
            if (!v.to_scene)
                fail(v.where, "coordinate reference system " + gdal::label(from),
                     "cannot be transformed to the scene's " + gdal::label(*scene_crs) + ": " + gdal::last_error());
            v.note = "reprojected from " + gdal::label(from) + " to the scene's " + gdal::label(*scene_crs);
        }
    }
    v.layer->ResetReading();
    return v;
}

std::unique_ptr<OGRGeometry> VectorLayer::geometry_in_scene(const OGRFeature& feature) const {
    const OGRGeometry* g = feature.GetGeometryRef();
    if (!g) return nullptr;
    std::unique_ptr<OGRGeometry> copy(g->clone());
    if (to_scene && copy->transform(to_scene.get()) != OGRERR_NONE)
        fail(where, "feature " + std::to_string(feature.GetFID()), "cannot be reprojected: " + gdal::last_error());
    return copy;
}

int VectorLayer::field_index(const std::string& field) const { return layer->GetLayerDefn()->GetFieldIndex(field.c_str()); }

std::string VectorLayer::field_names() const {
    std::string names;
    for (int k = 0; k < layer->GetLayerDefn()->GetFieldCount(); ++k)
        names += (k ? ", " : "") + std::string(layer->GetLayerDefn()->GetFieldDefn(k)->GetNameRef());
    return names.empty() ? std::string("none") : names;
}

}  // namespace flotsam
