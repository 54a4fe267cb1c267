// `flotsam export`: hazard maps as Cloud-Optimised GeoTIFF and tracks as GIS lines, in
// the scene's CRS, for QGIS and the other GIS tools (export/gis_export.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <optional>

#include "app/commands.hpp"
#include "common/cf.hpp"
#include "common/checks.hpp"
#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "common/output_lock.hpp"
#include "data/gdal_support.hpp"
#include "export/gis_export.hpp"

namespace flotsam {

namespace {

struct ExportOptions {
    std::string stats, scene, out_dir = "gis";
    std::vector<std::string> flows, trajectories;
    std::string tracks_format = "gpkg";
    std::string sources, hazard_regions;
    std::string project = "project.qgz";  // "" or "none": no project
};

// The style a written layer carries: a GeoPackage's default in layer_styles, else the
// .qml beside the file.
std::string style_of(const std::string& path, const std::string& layer) {
    if (std::filesystem::path(path).extension() == ".gpkg") return gis::qgis::stored_style(path, layer);
    std::ifstream in(std::filesystem::path(path).replace_extension(".qml"));
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Files of one scene only: the same CRS, the same cell size where both say, the same
// building mask where both record it (scene_buildings_sha256).
void check_same_scene(const gis::SceneOf& a, const gis::SceneOf& b) {
    cf::check_same_crs(a.path, a.crs, b.path, b.crs);
    if (a.cell > 0 && b.cell > 0 && std::fabs(a.cell - b.cell) > 1e-6 * std::max(a.cell, b.cell))
        fail(a.path, "",
             "comes from a scene of " + number_text(a.cell) + " m cells, " + b.path + " from one of " + number_text(b.cell) +
                 " m: one export combines the files of one scene (export them in two runs)");
    // A flow's window lies inside its scene, which the statistics' maps cover: one extent
    // holds the other (a cell of slack).
    if (a.extent.size() == 4 && b.extent.size() == 4) {
        const double slack = std::max(a.cell, b.cell) * 1.001;
        const auto inside = [&](const std::vector<double>& in, const std::vector<double>& out) {
            return in[0] >= out[0] - slack && in[1] <= out[1] + slack && in[2] >= out[2] - slack && in[3] <= out[3] + slack;
        };
        const auto text = [](const std::vector<double>& e) {
            return "x " + coordinate_text(e[0]) + " to " + coordinate_text(e[1]) + ", y " + coordinate_text(e[2]) + " to " +
                   coordinate_text(e[3]) + " m";
        };
        if (!inside(a.extent, b.extent) && !inside(b.extent, a.extent))
            fail(a.path, "x, y",
                 "covers " + text(a.extent) + ", " + b.path + " covers " + text(b.extent) +
                     ": neither lies within the other, so they are not of one scene (export them in two runs)");
    }
    if (!a.fingerprint.empty() && !b.fingerprint.empty() && a.fingerprint != b.fingerprint)
        fail(a.path, "",
             "comes from another scene than " + b.path + " (their scenes' grid or building mask differ: scene_buildings_sha256 " +
                 a.fingerprint + " and " + b.fingerprint +
                 "): one export combines the files of one scene (export them in two runs)");
}

// The QGIS project of what was written: its layers (top first within each group: points,
// lines, areas, the mesh, rasters, else in the order written), the view on the flows'
// window (else on everything, `extent`: x0, y0, x1, y1), the temporal controller stepping
// by the first flow's frames.
void write_study_project(const ExportOptions& o, const std::vector<gis::qgis::ProjectLayer>& layers, const cf::GridMapping& crs,
                         const Grid* window, double extent[4]) {
    using gis::qgis::ProjectLayer;
    std::vector<int> rank;
    for (const ProjectLayer& l : layers) {
        if (l.kind != ProjectLayer::Kind::vector) {
            rank.push_back(l.kind == ProjectLayer::Kind::mesh ? 3 : 4);
            continue;
        }
        const gdal::Dataset d = gdal::open_vector(l.path);
        OGRLayer* layer = d->GetLayerByName(l.layer.c_str());
        OGREnvelope e;
        if (layer->GetExtent(&e) == OGRERR_NONE) {
            extent[0] = std::min(extent[0], e.MinX);
            extent[1] = std::min(extent[1], e.MinY);
            extent[2] = std::max(extent[2], e.MaxX);
            extent[3] = std::max(extent[3], e.MaxY);
        }
        const OGRwkbGeometryType g = wkbFlatten(layer->GetGeomType());
        rank.push_back(g == wkbPoint || g == wkbMultiPoint ? 0 : g == wkbLineString || g == wkbMultiLineString ? 1 : 2);
    }
    std::vector<std::size_t> order(layers.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return rank[a] < rank[b]; });
    gis::qgis::Project p;
    p.title = "flotsam: " + (o.scene.empty() ? o.out_dir : std::filesystem::path(o.scene).stem().string());
    p.crs = crs;
    p.x_min = window ? window->x0 - 0.5 * window->dx : extent[0];
    p.y_min = window ? window->y0 - 0.5 * window->dy : extent[1];
    p.x_max = window ? window->x0 + (window->nx - 0.5) * window->dx : extent[2];
    p.y_max = window ? window->y0 + (window->ny - 0.5) * window->dy : extent[3];
    p.groups = {"sources", "regions", "buildings", "debris", "maps"};
    for (std::size_t k : order) p.layers.push_back(layers[k]);
    if (!o.flows.empty()) {
        const nc::File f = nc::File::open_read(o.flows[0]);
        const std::vector<double> time = nc::read_finite(f, "time");
        p.time_step = time.size() > 1 ? time[1] - time[0] : 1.0;
    }
    const std::string path = (std::filesystem::path(o.out_dir) / o.project).string();
    gis::qgis::write_project(path, p);
    std::printf("export: %s (QGIS project: %zu layers in groups sources, regions, buildings, debris, maps; %s)\n", path.c_str(),
                layers.size(), crs.empty() ? "no CRS: local metres" : crs.name().c_str());
}

// Positions of a file of tracks within the grid of another file of the export (a track
// off the flow's grid, off the statistics' maps): one cell of slack.
void check_positions(const gis::TrackLayer& tracks, const gis::SceneOf& grid_of) {
    if (grid_of.extent.size() != 4) return;
    const auto& e = grid_of.extent;
    const double slack = std::max(grid_of.cell, 1e-6 * (e[1] - e[0]));
    for (std::size_t b = 0; b < tracks.table.tracks.size(); ++b)
        debris::check_track_within(tracks.table.path, b, tracks.table.tracks[b], e[0] - slack, e[1] + slack, e[2] - slack,
                                   e[3] + slack, "the grid of " + grid_of.path);
}

// Everything the export reads, read and checked, each file and the files against each
// other, before anything is written.
struct ExportInputs {
    Grid stats_grid, flow_grid;
    cf::GridMapping stats_crs, flow_crs, study_crs;
    std::vector<gis::MapLayer> stats_layers, flow_layers;
    std::vector<gis::TrackLayer> tracks;
    std::optional<gis::BuildingLayer> buildings;
};

ExportInputs read_inputs(const ExportOptions& o) {
    ExportInputs in;
    std::vector<gis::SceneOf> scenes;
    if (!o.stats.empty()) {
        scenes.emplace_back();
        in.stats_layers = gis::stats_maps(o.stats, in.stats_grid, in.stats_crs, &scenes.back());
    }
    if (!o.flows.empty()) {
        scenes.emplace_back();
        in.flow_layers = gis::flow_maps(o.flows, in.flow_grid, in.flow_crs, &scenes.back());
    }
    const std::size_t gridded = scenes.size();
    for (const auto& t : o.trajectories) {
        scenes.emplace_back();
        in.tracks.push_back(gis::read_tracks(t, &scenes.back()));
        for (std::size_t g = 0; g < gridded; ++g) check_positions(in.tracks.back(), scenes[g]);
    }
    if (!o.hazard_regions.empty()) {
        scenes.push_back({o.hazard_regions, 0.0, "", {}, {}});
        gis::write_hazard_regions(o.hazard_regions, "", true, &scenes.back().crs);
    }
    for (std::size_t a = 1; a < scenes.size(); ++a) check_same_scene(scenes[a], scenes[0]);
    in.study_crs = scenes.empty() ? cf::GridMapping{} : scenes[0].crs;
    if (!o.sources.empty()) gis::write_sources(o.sources, in.study_crs, "", true);
    if (!o.scene.empty() && !o.stats.empty()) in.buildings = gis::read_buildings(o.scene, o.stats);
    // The debris maps cover what the flows cover (bodies move only where a flow is stored).
    if (!o.stats.empty() && !o.flows.empty()) gis::crop_maps(in.stats_layers, in.stats_grid, in.flow_grid);
    return in;
}

std::string out_path(const ExportOptions& o, const std::string& name) { return (std::filesystem::path(o.out_dir) / name).string(); }
std::string track_path(const ExportOptions& o, const std::string& t) {
    return out_path(o, std::filesystem::path(t).stem().string() + "_tracks." + o.tracks_format);
}
std::string qml_beside(const std::string& path) { return std::filesystem::path(path).replace_extension(".qml").string(); }

// Every file the export writes into --out-dir: the outputs of its guard.
std::vector<NamedPath> outputs_of(const ExportOptions& o, const ExportInputs& in, bool project) {
    std::vector<NamedPath> out;
    for (const auto* maps : {&in.stats_layers, &in.flow_layers})
        for (const auto& m : *maps) {
            out.push_back({"--out-dir", out_path(o, m.name + ".tif")});
            out.push_back({"--out-dir", qml_beside(out_path(o, m.name + ".tif"))});
        }
    for (const auto& t : o.trajectories) {
        out.push_back({"--out-dir", track_path(o, t)});
        if (o.tracks_format != "gpkg") out.push_back({"--out-dir", qml_beside(track_path(o, t))});
    }
    if (in.buildings) out.push_back({"--out-dir", out_path(o, "buildings.gpkg")});
    if (!o.scene.empty()) out.push_back({"--out-dir", out_path(o, "scene_features.gpkg")});
    if (!o.hazard_regions.empty()) out.push_back({"--out-dir", out_path(o, "hazard_regions.gpkg")});
    if (!o.sources.empty()) out.push_back({"--out-dir", out_path(o, "sources.gpkg")});
    if (project) out.push_back({"--project", out_path(o, o.project)});
    return out;
}

// The layers of the study besides maps and tracks: buildings, the scene's features, the
// hazard regions, the sources; each added to the project's layers.
void write_study_layers(const ExportOptions& o, const ExportInputs& in, std::vector<gis::qgis::ProjectLayer>& layers) {
    using gis::qgis::ProjectLayer;
    auto add_vector = [&](const std::string& path, const std::string& layer, const std::string& name, const std::string& group,
                          bool visible) {
        layers.push_back({ProjectLayer::Kind::vector, path, layer, name, group, visible, style_of(path, layer)});
    };
    if (in.buildings) {
        const std::string path = out_path(o, "buildings.gpkg");
        const std::size_t n = gis::write_buildings(*in.buildings, path);
        std::printf("export: %s (%zu building footprints with their impact statistics)\n", path.c_str(), n);
        add_vector(path, "buildings", "buildings: hit probability, p90 impact force", "buildings", true);
    }
    if (!o.scene.empty()) {
        const std::string path = out_path(o, "scene_features.gpkg");
        if (const std::size_t n = gis::write_scene_features(o.scene, path)) {
            std::printf("export: %s (%zu named points, sections and regions of the scene)\n", path.c_str(), n);
            const gdal::Dataset d = gdal::open_vector(path);
            const std::pair<const char*, const char*> shown[] = {
                {"starts", "debris starts"}, {"gauges", "gauges"}, {"sections", "passage sections"}, {"regions", "arrival regions"}};
            for (const auto& [layer, name] : shown)
                if (d->GetLayerByName(layer))
                    add_vector(path, layer, name,
                               layer == std::string("starts")   ? "sources"
                               : layer == std::string("gauges") ? "maps"
                                                                : "regions",
                               layer == std::string("starts"));
        }
    }
    if (!o.hazard_regions.empty()) {
        const std::string path = out_path(o, "hazard_regions.gpkg");
        const std::size_t n = gis::write_hazard_regions(o.hazard_regions, path);
        std::printf("export: %s (%zu hazard regions of the design standard)\n", path.c_str(), n);
        add_vector(path, "hazard_regions", "hazard regions (±22.5°)", "regions", false);
    }
    if (!o.sources.empty()) {
        const std::string path = out_path(o, "sources.gpkg");
        const std::size_t n = gis::write_sources(o.sources, in.study_crs, path);
        std::printf("export: %s (%zu debris sources in the scene's CRS)\n", path.c_str(), n);
        const gdal::Dataset d = gdal::open_vector(path);
        for (const char* layer : {"source_points", "source_areas"})
            if (d->GetLayerByName(layer))
                add_vector(path, layer, std::string("sources: ") + (layer == std::string("source_areas") ? "yards" : "bodies"),
                           "sources", true);
    }
}

void run_export(const ExportOptions& o) {
    if (o.stats.empty() && o.flows.empty() && o.trajectories.empty())
        fail("export", "inputs", "give at least one of --stats, --flow, --trajectories");
    std::vector<NamedPath> inputs = {
        {"--stats", o.stats}, {"--scene", o.scene}, {"--sources", o.sources, true}, {"--hazard-regions", o.hazard_regions}};
    for (const auto& f : o.flows) inputs.push_back({"--flow", f});
    for (const auto& t : o.trajectories) inputs.push_back({"--trajectories", t});
    for (const auto& i : inputs)
        if (!i.gis) check_input_file(i.option, i.path);
    check_gis_input("--sources", o.sources);
    const bool project = !o.project.empty() && o.project != "none";
    if (project && std::filesystem::path(o.project).extension() != ".qgz")
        fail("--project", o.project, "a QGIS project is written as .qgz (or give none)");
    const ExportInputs in = read_inputs(o);
    // Every file written into --out-dir, against every input (compared by inode) and each
    // other, before the first is written.
    const OutputGuard guard(outputs_of(o, in, project), inputs);

    using gis::qgis::ProjectLayer;
    std::vector<ProjectLayer> layers;
    double extent[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    auto cover = [&](double x0, double y0, double x1, double y1) {
        extent[0] = std::min(extent[0], x0);
        extent[1] = std::min(extent[1], y0);
        extent[2] = std::max(extent[2], x1);
        extent[3] = std::max(extent[3], y1);
    };
    auto write_maps = [&](const std::vector<gis::MapLayer>& maps, const Grid& g, const cf::GridMapping& crs,
                          const std::string& from, const std::string& group, const std::vector<std::string>& shown) {
        for (const auto& m : maps) {
            const std::string path = out_path(o, m.name + ".tif");
            gis::write_cog(path, g, crs, m, "flotsam export from " + from);
            std::printf("export: %s (%d x %d cells of %g m, %s)\n", path.c_str(), g.nx, g.ny, g.dx,
                        crs.empty() ? "no CRS: local metres" : crs.name().c_str());
            const bool visible = std::find(shown.begin(), shown.end(), m.name) != shown.end();
            const std::string units = m.units == "1" ? "" : m.units == "m s-1" ? " [m/s]" : " [" + m.units + "]";
            layers.push_back(
                {ProjectLayer::Kind::raster, path, "", m.title + units, group, visible, gis::qgis::raster_qml(m.style)});
        }
        cover(g.x0 - 0.5 * g.dx, g.y0 - 0.5 * g.dy, g.x0 + (g.nx - 0.5) * g.dx, g.y0 + (g.ny - 0.5) * g.dy);
    };
    if (!o.flows.empty()) {
        // The first flow in time, drawn over the maps when the temporal controller runs.
        ProjectLayer mesh = gis::flow_mesh_layer(o.flows[0], in.flow_layers[1].style.stops.back().value);  // the onshore range
        mesh.group = "maps";
        mesh.visible = false;
        layers.push_back(mesh);
        write_maps(in.flow_layers, in.flow_grid, in.flow_crs,
                   o.flows.size() == 1 ? o.flows[0] : std::to_string(o.flows.size()) + " flows", "maps",
                   {"inundation_depth", "max_depth"});
    }
    for (std::size_t k = 0; k < in.tracks.size(); ++k) {
        const std::string path = track_path(o, o.trajectories[k]);
        const std::size_t n = gis::write_tracks(in.tracks[k], path);
        std::printf("export: %s (%zu tracks)\n", path.c_str(), n);
        layers.push_back({ProjectLayer::Kind::vector, path, "tracks",
                          "tracks of " + std::filesystem::path(o.trajectories[k]).stem().string() + " (" + std::to_string(n) + ")",
                          "debris", true, style_of(path, "tracks")});
    }
    if (!o.stats.empty()) write_maps(in.stats_layers, in.stats_grid, in.stats_crs, o.stats, "debris", {"pass_probability_all"});
    write_study_layers(o, in, layers);
    if (project) write_study_project(o, layers, in.study_crs, o.flows.empty() ? nullptr : &in.flow_grid, extent);
}

}  // namespace

void register_export_commands(CLI::App& app) {
    auto o = std::make_shared<ExportOptions>();
    CLI::App* sub = app.add_subcommand(
        "export",
        "GIS out: hazard maps (pass probability and largest debris speed per body and model from --stats; maximum depth, "
        "maximum speed and arrival time from --flow, the envelope of several) as Cloud-Optimised GeoTIFF, and debris "
        "tracks (--trajectories: a debris or sweep file) as lines with their attributes, all in the scene's CRS");
    add_config_option(sub);
    sub->add_option("--stats", o->stats, "statistics file (flotsam stats)")->check(CLI::ExistingFile);
    sub->add_option("--flow", o->flows, "flow file (repeatable: the envelope of an ensemble)")->check(CLI::ExistingFile);
    sub->add_option("--trajectories", o->trajectories, "trajectory or sweep file (repeatable)")->check(CLI::ExistingFile);
    sub->add_option("--scene", o->scene,
                    "the study's scene: scene_features.gpkg (its debris starts, gauges, sections and regions) and, with "
                    "--stats, buildings.gpkg (its building footprints with their impact statistics)")
        ->check(CLI::ExistingFile);
    sub->add_option("--sources", o->sources,
                    "the study's debris sources (the vector file of flotsam debris --sources or a sweep's [[sources]]): "
                    "written as sources.gpkg in the scene's CRS")
        ->check(CLI::ExistingFile);
    sub->add_option("--hazard-regions", o->hazard_regions,
                    "hazard_regions.nc of pipelines/hazard_region.py: written as hazard_regions.gpkg (polygons)")
        ->check(CLI::ExistingFile);
    sub->add_option("--project", o->project, "the QGIS project of everything written, in --out-dir (.qgz; none: no project)")
        ->capture_default_str();
    sub->add_option("--out-dir", o->out_dir, "folder for the GeoTIFFs, GeoPackages and the project")->capture_default_str();
    sub->add_option("--tracks-format", o->tracks_format, "gpkg (GeoPackage), geojson or shp")
        ->check(CLI::IsMember({"gpkg", "geojson", "shp"}))
        ->capture_default_str();
    sub->callback([o] { run_export(*o); });
}

}  // namespace flotsam
