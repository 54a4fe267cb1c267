// `flotsam export`: hazard maps as Cloud-Optimised GeoTIFF and tracks as GIS lines, in
// the scene's CRS, for QGIS and the other GIS tools (export/gis_export.hpp).
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/commands.hpp"
#include "common/error.hpp"
#include "export/gis_export.hpp"

namespace flotsam {

namespace {

struct ExportOptions {
    std::string stats, out_dir = "gis";
    std::vector<std::string> flows, trajectories;
    std::string tracks_format = "gpkg";
};

void run_export(const ExportOptions& o) {
    if (o.stats.empty() && o.flows.empty() && o.trajectories.empty())
        fail("export", "inputs", "give at least one of --stats, --flow, --trajectories");
    auto write_maps = [&](const std::vector<gis::MapLayer>& maps, const Grid& g, const cf::GridMapping& crs,
                          const std::string& from) {
        for (const auto& m : maps) {
            const std::string path = (std::filesystem::path(o.out_dir) / (m.name + ".tif")).string();
            gis::write_cog(path, g, crs, m, "flotsam export from " + from);
            std::printf("export: %s (%d x %d cells of %g m, %s)\n", path.c_str(), g.nx, g.ny, g.dx,
                        crs.empty() ? "no CRS: local metres" : crs.name().c_str());
        }
    };
    if (!o.stats.empty()) {
        Grid g;
        cf::GridMapping crs;
        const auto maps = gis::stats_maps(o.stats, g, crs);
        write_maps(maps, g, crs, o.stats);
    }
    if (!o.flows.empty()) {
        Grid g;
        cf::GridMapping crs;
        const auto maps = gis::flow_maps(o.flows, g, crs);
        write_maps(maps, g, crs, o.flows.size() == 1 ? o.flows[0] : std::to_string(o.flows.size()) + " flows");
    }
    for (const auto& t : o.trajectories) {
        const std::string stem = std::filesystem::path(t).stem().string();
        const std::string path = (std::filesystem::path(o.out_dir) / (stem + "_tracks." + o.tracks_format)).string();
        const std::size_t n = gis::write_tracks(t, path);
        std::printf("export: %s (%zu tracks)\n", path.c_str(), n);
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
    sub->add_option("--out-dir", o->out_dir, "folder for the GeoTIFFs and track files")->capture_default_str();
    sub->add_option("--tracks-format", o->tracks_format, "gpkg (GeoPackage), geojson or shp")
        ->check(CLI::IsMember({"gpkg", "geojson", "shp"}))
        ->capture_default_str();
    sub->callback([o] { run_export(*o); });
}

}  // namespace flotsam
