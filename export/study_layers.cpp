// The study's other layers (export/gis_export.hpp): its debris sources, the design
// standard's hazard regions and the scene's named features, as GeoPackages in its CRS.
#include <cmath>
#include <map>
#include <memory>
#include <optional>

#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "export/gis_export.hpp"
#include "export/styles.hpp"
#include "export/vector_output.hpp"
#include "formats/scene.hpp"

namespace flotsam::gis {

namespace {

// A debris source of a study, carried into the scene's CRS.
struct Source {
    std::string layer, type;
    GIntBig feature = 0;
    int count = 0;
    bool has_count = false;
    std::unique_ptr<OGRGeometry> geometry;
};

// Every feature of every layer of `in`, carried into `target` (the scene's CRS; none:
// local metres), as an area or a point.
void read_sources(GDALDataset* in, const std::string& sources_path, const std::optional<OGRSpatialReference>& target,
                  std::vector<Source>& areas, std::vector<Source>& points) {
    for (int l = 0; l < in->GetLayerCount(); ++l) {
        OGRLayer* layer = in->GetLayer(l);
        const OGRSpatialReference* from = gdal::layer_crs(*layer);
        if (bool(from) != bool(target))
            fail(sources_path, std::string("layer '") + layer->GetName() + "'",
                 from ? "has a CRS and the scene has none (local metres)" : "has no CRS and the scene has one");
        std::unique_ptr<OGRCoordinateTransformation> to_scene;
        if (from && !from->IsSame(&*target)) {
            OGRSpatialReference source_crs(*from);
            source_crs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
            to_scene.reset(OGRCreateCoordinateTransformation(&source_crs, &*target));
            if (!to_scene)
                fail(sources_path, std::string("layer '") + layer->GetName() + "'", "cannot be carried into the scene's CRS");
        }
        const int type_field = layer->GetLayerDefn()->GetFieldIndex("type");
        const int count_field = layer->GetLayerDefn()->GetFieldIndex("count");
        layer->ResetReading();
        for (OGRFeature* raw; (raw = layer->GetNextFeature()) != nullptr;) {
            std::unique_ptr<OGRFeature, void (*)(OGRFeature*)> f(raw, OGRFeature::DestroyFeature);
            const OGRGeometry* geometry = f->GetGeometryRef();
            if (!geometry) continue;
            Source s{layer->GetName(),
                     type_field >= 0 ? f->GetFieldAsString(type_field) : "",
                     f->GetFID(),
                     count_field >= 0 ? f->GetFieldAsInteger(count_field) : 0,
                     count_field >= 0 && f->IsFieldSetAndNotNull(count_field),
                     std::unique_ptr<OGRGeometry>(geometry->clone())};
            if (to_scene && s.geometry->transform(to_scene.get()) != OGRERR_NONE)
                fail(sources_path, s.layer + " feature " + std::to_string(s.feature), "cannot be carried into the scene's CRS");
            const auto flat = wkbFlatten(s.geometry->getGeometryType());
            if (flat == wkbPolygon || flat == wkbMultiPolygon) {
                s.geometry.reset(OGRGeometryFactory::forceToMultiPolygon(s.geometry.release()));
                areas.push_back(std::move(s));
            } else if (flat == wkbPoint) {
                points.push_back(std::move(s));
            } else {
                fail(sources_path, s.layer + " feature " + std::to_string(s.feature), "is neither a point nor a polygon");
            }
        }
    }
}

}  // namespace

std::size_t write_sources(const std::string& sources_path, const cf::GridMapping& crs, const std::string& out_path,
                          bool check_only) {
    gdal::init();
    gdal::Dataset in = gdal::open_vector(sources_path);
    std::optional<OGRSpatialReference> target;
    if (!crs.empty()) {
        target = gdal::spatial_ref(crs, out_path);
        target->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    }
    std::vector<Source> areas, points;
    read_sources(in.get(), sources_path, target, areas, points);
    if (areas.empty() && points.empty()) fail(sources_path, "", "holds no point or polygon feature: no debris source to export");
    if (check_only) return areas.size() + points.size();
    auto writer = [&out_path](std::vector<Source>& sources) {
        return [&out_path, list = &sources](OGRLayer& layer) {
            add_field(layer, out_path, "layer", OFTString);
            add_field(layer, out_path, "feature", OFTInteger64);
            add_field(layer, out_path, "type", OFTString);
            add_field(layer, out_path, "count", OFTInteger);
            for (Source& s : *list) {
                OGRFeature feature(layer.GetLayerDefn());
                feature.SetField("layer", s.layer.c_str());
                feature.SetField("feature", s.feature);
                if (!s.type.empty()) feature.SetField("type", s.type.c_str());
                if (s.has_count) feature.SetField("count", s.count);
                feature.SetGeometry(s.geometry.get());
                if (layer.CreateFeature(&feature) != OGRERR_NONE)
                    fail_writing(out_path, s.layer + " feature " + std::to_string(s.feature), "write it");
            }
            return list->size();
        };
    };
    std::vector<VectorLayerDef> defs;
    if (!areas.empty())
        defs.push_back({"source_areas",
                        wkbMultiPolygon,
                        {{"outlined", "the yards, outlined and labelled", styles::sources_qml(false, styles::source_label), true}},
                        writer(areas)});
    if (!points.empty())
        defs.push_back({"source_points",
                        wkbPoint,
                        {{"points", "single bodies, labelled", styles::sources_qml(true, styles::source_label), true}},
                        writer(points)});
    return write_vector_layers(out_path, "GPKG", crs, sources_path, defs);
}

std::size_t write_hazard_regions(const std::string& regions_path, const std::string& out_path, bool check_only,
                                 cf::GridMapping* crs_out) {
    gdal::init();
    const nc::File f = nc::File::open_read(regions_path);
    for (const char* v : {"x", "y", "source", "region_inflow", "region_outflow"})
        if (!f.has_var(v))
            fail(regions_path, std::string("variable '") + v + "'",
                 "missing: not hazard regions written by pipelines/hazard_region.py");
    const Grid g = grid_from_coordinates(nc::read_finite(f, "x"), nc::read_finite(f, "y"), f.path());
    const cf::GridMapping crs = cf::read_crs(f, "region_inflow");
    if (crs_out) *crs_out = crs;
    const std::vector<std::string> sources = f.get_strings(f.var("source"));
    struct Region {
        std::string source, flow;
        int cells;
        OGRMultiPolygon shape;
    };
    std::vector<Region> regions;
    for (const auto& [name, flow] : {std::pair{"region_inflow", "inflow"}, std::pair{"region_outflow", "return flow"}}) {
        const int v = f.var(name);
        if (f.shape(v) != std::vector<std::size_t>{sources.size(), std::size_t(g.ny), std::size_t(g.nx)})
            fail(regions_path, std::string("variable '") + name + "'", "must be on (source, y, x)");
        if (check_only) continue;
        const std::vector<int> mask = f.get_int(v);
        for (std::size_t k = 0; k < sources.size(); ++k) {
            std::vector<std::int32_t> ids(g.size());
            int cells = 0;
            for (std::size_t c = 0; c < g.size(); ++c) cells += ids[c] = mask[k * g.size() + c] != 0;
            if (cells == 0) continue;
            std::map<int, OGRMultiPolygon> pieces = polygons_of(g, ids, out_path);
            std::unique_ptr<OGRGeometry> joined(pieces[1].UnionCascaded());
            if (!joined) fail(out_path, sources[k] + " " + flow, "GDAL could not join its cells: " + gdal::last_error());
            std::unique_ptr<OGRGeometry> multi(OGRGeometryFactory::forceToMultiPolygon(joined.release()));
            regions.push_back({sources[k], flow, cells, *multi->toMultiPolygon()});
        }
    }
    if (check_only) return sources.size();
    return write_vector_layers(
        out_path, "GPKG", crs, regions_path,
        {{"hazard_regions",
          wkbMultiPolygon,
          {{"by flow", "the design standard's regions, hatched by flow direction", styles::hazard_regions_qml(), true}},
          [&](OGRLayer& layer) {
              add_field(layer, out_path, "source", OFTString);
              add_field(layer, out_path, "flow", OFTString);
              add_field(layer, out_path, "cells", OFTInteger);
              add_field(layer, out_path, "area_m2", OFTReal);
              for (Region& r : regions) {
                  OGRFeature feature(layer.GetLayerDefn());
                  feature.SetField("source", r.source.c_str());
                  feature.SetField("flow", r.flow.c_str());
                  feature.SetField("cells", r.cells);
                  feature.SetField("area_m2", r.cells * g.dx * g.dy);
                  feature.SetGeometry(&r.shape);
                  if (layer.CreateFeature(&feature) != OGRERR_NONE) fail_writing(out_path, r.source, "write it");
              }
              return regions.size();
          }}});
}

std::size_t write_scene_features(const std::string& scene_path, const std::string& out_path) {
    gdal::init();
    const Scene scene = read_scene(scene_path);
    auto name_field = [&](OGRLayer& layer) { add_field(layer, out_path, "name", OFTString); };
    auto add = [&](OGRLayer& layer, const std::string& name, const OGRGeometry& g, double heading = std::nan("")) {
        OGRFeature feature(layer.GetLayerDefn());
        feature.SetField("name", name.c_str());
        if (!std::isnan(heading)) feature.SetField("heading_deg", heading);
        feature.SetGeometry(&g);
        if (layer.CreateFeature(&feature) != OGRERR_NONE) fail_writing(out_path, name, "write it");
    };
    std::vector<VectorLayerDef> defs;
    for (const char* kind : {"start", "gauge"}) {
        std::vector<ScenePoint> points;
        for (const ScenePoint& p : scene.points)
            if (p.kind == kind) points.push_back(p);
        if (points.empty()) continue;
        const bool start = std::string(kind) == "start";
        defs.push_back({start ? "starts" : "gauges",
                        wkbPoint,
                        {{"labelled", start ? "the scene's debris starts" : "the scene's gauges",
                          start ? styles::sources_qml(true, "\"name\"") : styles::feature_qml(qgis::Symbol::Kind::marker), true}},
                        [&, points, start](OGRLayer& layer) {
                            name_field(layer);
                            if (start) add_field(layer, out_path, "heading_deg", OFTReal);
                            for (const ScenePoint& p : points)
                                add(layer, p.name, OGRPoint(p.x, p.y), start ? p.heading_deg : std::nan(""));
                            return points.size();
                        }});
    }
    if (!scene.sections.empty())
        defs.push_back({"sections",
                        wkbLineString,
                        {{"labelled", "the passage sections", styles::feature_qml(qgis::Symbol::Kind::line), true}},
                        [&](OGRLayer& layer) {
                            name_field(layer);
                            for (const Section& c : scene.sections) {
                                OGRLineString line;
                                line.addPoint(c.x, c.y_min);
                                line.addPoint(c.x, c.y_max);
                                add(layer, c.name, line);
                            }
                            return scene.sections.size();
                        }});
    if (!scene.regions.empty())
        defs.push_back({"regions",
                        wkbPolygon,
                        {{"labelled", "the arrival-count regions", styles::feature_qml(qgis::Symbol::Kind::fill), true}},
                        [&](OGRLayer& layer) {
                            name_field(layer);
                            for (const Region& r : scene.regions) {
                                OGRLinearRing ring;
                                for (const auto& v : r.polygon) ring.addPoint(v[0], v[1]);
                                ring.closeRings();
                                OGRPolygon polygon;
                                polygon.addRing(&ring);
                                add(layer, r.name, polygon);
                            }
                            return scene.regions.size();
                        }});
    if (defs.empty()) return 0;
    return write_vector_layers(out_path, "GPKG", scene.crs, scene_path, defs);
}

}  // namespace flotsam::gis
