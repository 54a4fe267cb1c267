// The tracks layer (export/gis_export.hpp): a trajectory or sweep file read and checked,
// each track's summary and source, and the lines written.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "common/error.hpp"
#include "common/settings_nc.hpp"
#include "debris/body.hpp"
#include "export/gis_export.hpp"
#include "export/styles.hpp"
#include "export/vector_output.hpp"
#include "sweep/sweep_file.hpp"

namespace flotsam::gis {

TrackSummary track_summary(const std::vector<double>& time, const debris::Track& t) {
    TrackSummary s;
    if (time.empty()) return s;
    s.t_start = time.front();
    s.t_end = time.back();
    for (std::size_t k = 1; k < t.x.size(); ++k) s.path_length += std::hypot(t.x[k] - t.x[k - 1], t.y[k] - t.y[k - 1]);
    for (std::size_t k = 0; k < t.u.size() && k < t.v.size(); ++k) s.max_speed = std::max(s.max_speed, std::hypot(t.u[k], t.v[k]));
    return s;
}

namespace {

debris::TrajectoryColumn* text_column(debris::TrajectoryTable& t, const std::string& name) {
    for (debris::TrajectoryColumn& c : t.columns)
        if (c.name == name && c.type == NC_STRING) return &c;
    return nullptr;
}

// `source`: where each track's body came from, the GIS feature (a yard's bodies share it)
// or else the body itself; the tracks are coloured by it.
void add_sources(debris::TrajectoryTable& t, const sweep::SweepResult* sweep) {
    const std::size_t n = t.tracks.size();
    if (debris::TrajectoryColumn* source = text_column(t, "source")) {  // a debris file: empty where the body has no feature
        const debris::TrajectoryColumn* id = text_column(t, "trajectory_id");
        for (std::size_t b = 0; b < n; ++b)
            if (source->text[b].empty() && id) source->text[b] = id->text[b];
    } else if (const debris::TrajectoryColumn* body = text_column(t, "body"); body && sweep) {  // a sweep file: its body table
        debris::TrajectoryColumn c{"source", NC_STRING, {}, {}};
        for (std::size_t b = 0; b < n; ++b) {
            const auto k = std::size_t(std::find(sweep->bodies.begin(), sweep->bodies.end(), body->text[b]) - sweep->bodies.begin());
            c.text.push_back(k < sweep->body_sources.size() && !sweep->body_sources[k].empty() ? sweep->body_sources[k] : body->text[b]);
        }
        t.columns.push_back(std::move(c));
    }
}

OGRFieldType field_type(nc_type t) {
    return t == NC_STRING ? OFTString : (t == NC_INT || t == NC_BYTE || t == NC_SHORT) ? OFTInteger : OFTReal;
}

}  // namespace

TrackLayer read_tracks(const std::string& trajectory_path, SceneOf* scene) {
    // The bodies' settings, where the file has them, in their units and ranges as every
    // reader of them checks them (a width of 1e30 m was exported as an attribute).
    const auto check_bodies = [](const nc::File& f, std::size_t n) {
        std::vector<debris::BodyDef> defs(n);
        for (const auto* table : {&debris::body_shape_settings(), &debris::body_coefficient_settings(), &debris::body_model_settings()})
            get_setting_vars(f, *table, defs, "", false);
    };
    TrackLayer layer{debris::read_trajectory_table(trajectory_path, check_bodies), {}};
    // A sweep file's member table refers to its own tables (flows, bodies, variants,
    // parameter sets): checked as the sweep's reader checks it.
    if (layer.table.kind == "sweep") {
        const sweep::SweepResult tables = sweep::read_sweep_tables(trajectory_path);
        add_sources(layer.table, &tables);
    } else {
        add_sources(layer.table, nullptr);
    }
    for (const debris::Track& t : layer.table.tracks) layer.summaries.push_back(track_summary(layer.table.time, t));
    if (scene) *scene = SceneOf{trajectory_path, 0.0, layer.table.scene_buildings_sha256, layer.table.crs, {}};
    return layer;
}

const char* vector_driver_of(const std::string& out_path) {
    const std::string ext = std::filesystem::path(out_path).extension().string();
    if (ext == ".gpkg") return "GPKG";
    if (ext == ".geojson" || ext == ".json") return "GeoJSON";
    if (ext == ".shp") return "ESRI Shapefile";
    fail(out_path, "extension", "'" + ext + "': use .gpkg (GeoPackage), .geojson or .shp");
}

std::size_t write_tracks(const TrackLayer& tracks, const std::string& out_path) {
    gdal::init();
    const debris::TrajectoryTable& table = tracks.table;
    std::vector<std::string> source_names;
    for (const debris::TrajectoryColumn& c : table.columns)
        if (c.name == "source" && c.type == NC_STRING)
            for (const std::string& name : c.text)
                if (std::find(source_names.begin(), source_names.end(), name) == source_names.end()) source_names.push_back(name);
    const std::vector<qgis::NamedStyle> styles = {
        {"tracks by source", "thin translucent lines, one colour per debris source", styles::tracks_qml(source_names), true}};
    const auto write = [&](OGRLayer& layer) {
        for (const auto& c : table.columns) add_field(layer, out_path, c.name, field_type(c.type));
        for (const char* name : {"t_start", "t_end", "path_length", "max_speed"}) add_field(layer, out_path, name, OFTReal);
        std::size_t written = 0;
        for (std::size_t b = 0; b < table.tracks.size(); ++b) {
            const debris::Track& t = table.tracks[b];
            if (t.x.empty()) continue;
            OGRLineString line;
            for (std::size_t k = 0; k < t.x.size(); ++k) line.addPoint(t.x[k], t.y[k]);
            if (line.getNumPoints() == 1) line.addPoint(t.x[0], t.y[0]);  // one sample: a line needs two points
            OGRFeature feature(layer.GetLayerDefn());
            for (std::size_t c = 0; c < table.columns.size(); ++c) {
                const auto& col = table.columns[c];
                if (col.type == NC_STRING)
                    feature.SetField(int(c), col.text[b].c_str());
                else if (field_type(col.type) == OFTInteger)
                    feature.SetField(int(c), int(col.number[b]));
                else
                    feature.SetField(int(c), col.number[b]);
            }
            const TrackSummary& s = tracks.summaries[b];
            feature.SetField("t_start", s.t_start);
            feature.SetField("t_end", s.t_end);
            feature.SetField("path_length", s.path_length);
            feature.SetField("max_speed", s.max_speed);
            feature.SetGeometry(&line);
            if (layer.CreateFeature(&feature) != OGRERR_NONE) fail_writing(out_path, "trajectory " + std::to_string(b), "write it");
            ++written;
        }
        return written;
    };
    return write_vector_layers(out_path, vector_driver_of(out_path), table.crs, table.path, {{"tracks", wkbLineString, styles, write}});
}

}  // namespace flotsam::gis
