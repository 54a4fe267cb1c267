// The buildings layer (export/gis_export.hpp): the scene's building footprints with the
// impact statistics of a statistics file, checked against each other, then written.
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

#include "common/checks.hpp"
#include "common/error.hpp"
#include "export/gis_export.hpp"
#include "export/styles.hpp"
#include "export/vector_output.hpp"
#include "formats/scene.hpp"
#include "formats/stats_file.hpp"

namespace flotsam::gis {

namespace {

const stats_file::BuildingVariables& b = stats_file::building_all;
const stats_file::Variable* const columns[] = {&b.hit_probability, &b.first_hit_time, &b.impact_count, &b.speed_median, &b.speed_p90,
                                               &b.speed_max,       &b.force_median,   &b.force_p90,    &b.force_max};
const char* const field_names[] = {"hit_probability", "first_hit_time_s", "impacts",     "speed_median_m_s", "speed_p90_m_s",
                                   "speed_max_m_s",   "force_median_N",   "force_p90_N", "force_max_N"};

// The statistics' map grid is the scene's, coarsened by map_coarsen from its south-west
// corner (sweep/sweep_stats.cpp): statistics moved off their scene are refused here.
void check_map_grid(const nc::File& st, const Scene& scene) {
    const Grid m = stats_file::map_grid(st), &s = scene.grid;
    const int c = int(st.att_double(NC_GLOBAL, stats_file::attribute::map_coarsen).value_or(1.0));
    const Grid want{(s.nx + c - 1) / c, (s.ny + c - 1) / c, s.x_min_edge() + 0.5 * c * s.dx, s.y_min_edge() + 0.5 * c * s.dy,
                    c * s.dx, c * s.dy};
    const double tol = 1e-6 * std::max(want.dx, want.dy);
    if (m.nx != want.nx || m.ny != want.ny || std::fabs(m.x0 - want.x0) > tol || std::fabs(m.y0 - want.y0) > tol ||
        std::fabs(m.dx - want.dx) > tol || std::fabs(m.dy - want.dy) > tol)
        fail(st.path(), "variables 'x', 'y'",
             "the maps' grid (" + std::to_string(m.nx) + " x " + std::to_string(m.ny) + " cells of " + number_text(m.dx) +
                 " m from x = " + coordinate_text(m.x_min_edge()) + ", y = " + coordinate_text(m.y_min_edge()) +
                 " m) is not that of " + scene.path + " coarsened by map_coarsen " + std::to_string(c) + " (" +
                 std::to_string(want.nx) + " x " + std::to_string(want.ny) + " cells of " + number_text(want.dx) +
                 " m from x = " + coordinate_text(want.x_min_edge()) + ", y = " + coordinate_text(want.y_min_edge()) +
                 " m): the statistics were not computed on this scene");
}

}  // namespace

BuildingLayer read_buildings(const std::string& scene_path, const std::string& stats_path) {
    const Scene scene = read_scene(scene_path);
    BuildingLayer layer{scene_path, scene.grid, scene.crs, scene_building_ids(scene), {}, {}};
    if (std::none_of(layer.ids.begin(), layer.ids.end(), [](std::int32_t id) { return id > 0; }))
        fail(scene_path, "variable 'building'", "the scene has no buildings to export");
    const nc::File st = stats_file::open_checked(stats_path, "--stats");
    const std::string fingerprint = st.att_text(NC_GLOBAL, stats_file::attribute::scene_buildings_sha256).value_or("");
    if (!fingerprint.empty() && fingerprint != scene_buildings_sha256(scene))
        fail(stats_path, "scene_buildings_sha256", "comes from another scene than " + scene_path + " (grid or building mask differ)");
    check_map_grid(st, scene);
    cf::check_same_crs(stats_path, cf::read_crs(st, stats_file::pass_probability.name), scene_path, scene.crs);
    if (!st.has_var(stats_file::building_id.name))
        fail(stats_path, "variable 'building_id'", "missing: statistics written before impacts were recorded (run flotsam stats again)");
    for (const double id : stats_file::read_values(st, stats_file::building_id)) layer.stat_ids.push_back(int(id));
    for (const auto* c : columns) {
        layer.values.push_back(stats_file::read_values(st, *c));
        if (layer.values.back().size() != layer.stat_ids.size())
            fail(stats_path, std::string("variable '") + c->name + "'", "is not on dimension 'building'");
    }
    return layer;
}

std::size_t write_buildings(const BuildingLayer& layer, const std::string& out_path) {
    gdal::init();
    const Grid& g = layer.grid;
    std::map<int, OGRMultiPolygon> by_id = polygons_of(g, layer.ids, out_path);
    std::map<int, int> cells;
    for (std::int32_t id : layer.ids)
        if (id > 0) ++cells[id];
    const std::vector<qgis::NamedStyle> styles = {
        {"hit probability", "footprints by the share of tracks that hit them; label: the 90th-percentile impact force",
         styles::buildings_qml(), true},
        {"p90 force", "footprints by the 90th-percentile impact force", styles::buildings_force_qml(), false}};
    const auto write = [&](OGRLayer& out) {
        std::size_t written = 0;
        add_field(out, out_path, "building_id", OFTInteger);
        add_field(out, out_path, "cells", OFTInteger);
        add_field(out, out_path, "area_m2", OFTReal);
        for (std::size_t c = 0; c < 9; ++c) add_field(out, out_path, field_names[c], c == 2 ? OFTInteger : OFTReal);
        for (auto& [id, parts] : by_id) {
            std::unique_ptr<OGRGeometry> joined(parts.UnionCascaded());
            if (!joined) fail(out_path, "building " + std::to_string(id), "GDAL could not join its cells: " + gdal::last_error());
            std::unique_ptr<OGRGeometry> multi(OGRGeometryFactory::forceToMultiPolygon(joined.release()));
            OGRFeature feature(out.GetLayerDefn());
            feature.SetField("building_id", id);
            feature.SetField("cells", cells[id]);
            feature.SetField("area_m2", double(cells[id]) * g.dx * g.dy);
            const auto k = std::find(layer.stat_ids.begin(), layer.stat_ids.end(), id);
            for (std::size_t c = 0; c < 9; ++c) {
                const double v = k == layer.stat_ids.end() ? std::nan("") : layer.values[c][std::size_t(k - layer.stat_ids.begin())];
                if (c == 0 || c == 2)
                    feature.SetField(field_names[c], std::isnan(v) ? 0.0 : v);  // never hit: 0 and no impacts
                else if (std::isfinite(v))
                    feature.SetField(field_names[c], v);
                else
                    feature.SetFieldNull(feature.GetFieldIndex(field_names[c]));
            }
            feature.SetGeometry(multi.get());
            if (out.CreateFeature(&feature) != OGRERR_NONE) fail_writing(out_path, "building " + std::to_string(id), "write it");
            ++written;
        }
        return written;
    };
    return write_vector_layers(out_path, "GPKG", layer.crs, layer.scene_path, {{"buildings", wkbMultiPolygon, styles, write}});
}

}  // namespace flotsam::gis
