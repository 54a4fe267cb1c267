// `flotsam export`: hazard maps as Cloud-Optimised GeoTIFF and tracks as GIS lines, in
// the scene's CRS, for QGIS and the other GIS tools (export/gis_export.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/commands.hpp"
#include "common/cf.hpp"
#include "common/checks.hpp"
#include "common/error.hpp"
#include "export/gis_export.hpp"

namespace flotsam {

namespace {

struct ExportOptions {
    std::string stats, scene, out_dir = "gis";
    std::vector<std::string> flows, trajectories;
    std::string tracks_format = "gpkg";
};

// Files of one scene only: the same CRS, the same cell size where both say, the same
// building mask where both record it (scene_buildings_sha256).
void check_same_scene(const gis::SceneOf& a, const gis::SceneOf& b) {
    cf::check_same_crs(a.path, a.crs, b.path, b.crs);
    if (a.cell > 0 && b.cell > 0 && std::fabs(a.cell - b.cell) > 1e-6 * std::max(a.cell, b.cell))
        fail(a.path, "",
             "comes from a scene of " + number_text(a.cell) + " m cells, " + b.path + " from one of " + number_text(b.cell) +
                 " m: one export combines the files of one scene (export them in two runs)");
    if (!a.fingerprint.empty() && !b.fingerprint.empty() && a.fingerprint != b.fingerprint)
        fail(a.path, "",
             "comes from another scene than " + b.path + " (their scenes' grid or building mask differ: scene_buildings_sha256 " +
                 a.fingerprint + " and " + b.fingerprint +
                 "): one export combines the files of one scene (export them in two runs)");
}

void run_export(const ExportOptions& o) {
    if (o.stats.empty() && o.flows.empty() && o.trajectories.empty())
        fail("export", "inputs", "give at least one of --stats, --flow, --trajectories");
    check_input_file("--stats", o.stats);
    for (const auto& f : o.flows) check_input_file("--flow", f);
    for (const auto& t : o.trajectories) check_input_file("--trajectories", t);
    // Everything is read and checked, each file and the files against each other, before
    // anything is written.
    std::vector<gis::SceneOf> scenes;
    Grid stats_grid, flow_grid;
    cf::GridMapping stats_crs, flow_crs;
    std::vector<gis::MapLayer> stats_layers, flow_layers;
    if (!o.stats.empty()) {
        scenes.emplace_back();
        stats_layers = gis::stats_maps(o.stats, stats_grid, stats_crs, &scenes.back());
    }
    if (!o.flows.empty()) {
        scenes.emplace_back();
        flow_layers = gis::flow_maps(o.flows, flow_grid, flow_crs, &scenes.back());
    }
    auto track_path = [&](const std::string& t) {
        const std::string stem = std::filesystem::path(t).stem().string();
        return (std::filesystem::path(o.out_dir) / (stem + "_tracks." + o.tracks_format)).string();
    };
    for (const auto& t : o.trajectories) {
        scenes.emplace_back();
        gis::write_tracks(t, track_path(t), &scenes.back(), true);
    }
    for (std::size_t a = 1; a < scenes.size(); ++a) check_same_scene(scenes[a], scenes[0]);
    auto write_maps = [&](const std::vector<gis::MapLayer>& maps, const Grid& g, const cf::GridMapping& crs,
                          const std::string& from) {
        for (const auto& m : maps) {
            const std::string path = (std::filesystem::path(o.out_dir) / (m.name + ".tif")).string();
            gis::write_cog(path, g, crs, m, "flotsam export from " + from);
            std::printf("export: %s (%d x %d cells of %g m, %s)\n", path.c_str(), g.nx, g.ny, g.dx,
                        crs.empty() ? "no CRS: local metres" : crs.name().c_str());
        }
    };
    if (!o.stats.empty()) write_maps(stats_layers, stats_grid, stats_crs, o.stats);
    if (!o.flows.empty())
        write_maps(flow_layers, flow_grid, flow_crs, o.flows.size() == 1 ? o.flows[0] : std::to_string(o.flows.size()) + " flows");
    for (const auto& t : o.trajectories) {
        const std::string path = track_path(t);
        const std::size_t n = gis::write_tracks(t, path);
        std::printf("export: %s (%zu tracks)\n", path.c_str(), n);
    }
    if (!o.scene.empty()) {
        if (o.stats.empty()) fail("--scene", o.scene, "needs --stats (the buildings layer carries its impact statistics)");
        const std::string path = (std::filesystem::path(o.out_dir) / "buildings.gpkg").string();
        const std::size_t n = gis::write_building_footprints(o.scene, o.stats, path);
        std::printf("export: %s (%zu building footprints with their impact statistics)\n", path.c_str(), n);
    }
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
                    "scene of --stats: also write buildings.gpkg, its building footprints with their impact statistics")
        ->check(CLI::ExistingFile);
    sub->add_option("--out-dir", o->out_dir, "folder for the GeoTIFFs and track files")->capture_default_str();
    sub->add_option("--tracks-format", o->tracks_format, "gpkg (GeoPackage), geojson or shp")
        ->check(CLI::IsMember({"gpkg", "geojson", "shp"}))
        ->capture_default_str();
    sub->callback([o] { run_export(*o); });
}

}  // namespace flotsam
