// Command-line surface of the data stage: `scene generate`, `scene import`,
// `boundary generate`.
#include <cmath>
#include <cstdio>
#include <string>

#include "app/commands.hpp"
#include "common/checks.hpp"
#include "common/error.hpp"
#include "common/output_lock.hpp"
#include "data/boundary_generator.hpp"
#include "data/dem_import.hpp"
#include "data/scene_generator.hpp"
#include "formats/scene.hpp"

namespace flotsam {

namespace {

void register_scene_generate(CLI::App* scene, const std::string& command_line) {
    auto def = std::make_shared<SceneGenDef>();
    auto out = std::make_shared<std::string>();
    CLI::App* sub =
        scene->add_subcommand("generate",
                              "Write the synthetic analogue of the Kainan port-city flume (SCENE.md) at any grid spacing; "
                              "deterministic from --seed; marked synthetic in its metadata");
    sub->add_option("--resolution", def->resolution, "grid spacing [m], e.g. 0.01, 0.02, 0.04")
        ->capture_default_str()
        ->check(in_range(Range::positive("m").up_to(100.0)));
    sub->add_option("--seed", def->seed, "seed of the building layout")->capture_default_str();
    sub->add_option("--out", *out, "output scene file (NetCDF)")->required();
    sub->add_option("--lot-build-probability", def->lot_build_probability, "chance that a city lot holds a building")
        ->capture_default_str()
        ->check(in_range(Range::closed(0.0, 1.0)));
    add_config_option(sub);
    sub->callback([def, out, command_line] {
        const OutputGuard guard({{"--out", *out}}, {});
        const GeneratedScene g = generate_scene(*def);
        write_scene(*out, g.scene, command_line);
        std::printf("scene: %s (%d x %d cells of %.4g m, synthetic)\n", out->c_str(), g.scene.grid.nx, g.scene.grid.ny,
                    def->resolution);
    });
}

void register_scene_import(CLI::App* scene, const std::string& command_line) {
    auto def = std::make_shared<ImportDef>();
    auto out = std::make_shared<std::string>();
    auto extent = std::make_shared<std::vector<double>>();
    CLI::App* sub = scene->add_subcommand(
        "import",
        "Import a user DEM as a scene: any raster GDAL reads (GeoTIFF, ESRI ASCII grid, NetCDF, ...) in a projected CRS "
        "in metres (or local metres), resampled to --resolution (cell-area average when coarsening, bilinear when "
        "refining), with points, sections, regions, Manning rules and a building rule from --features (TOML; see "
        "docs/scene.md), building footprints from a vector file, and Manning n from a land-use raster or polygons. "
        "Without --features, a DEM with the Kainan extent gets the Kainan defaults; any other DEM gets no features "
        "and no Manning field.");
    sub->add_option("--dem", def->dem_path, "DEM file (GeoTIFF, .asc, NetCDF, or anything GDAL reads)")->required();
    sub->add_option("--features", def->features_path, "features TOML file");
    sub->add_option("--resolution", def->resolution, "grid spacing of the scene [m]")
        ->capture_default_str()
        ->check(in_range(Range::positive("m").up_to(1e5)));
    sub->add_option("--out", *out, "output scene file (NetCDF)")->required();
    GisImportDef& g = def->gis;
    sub->add_option("--crs", g.assign_crs,
                    "the DEM's CRS when its file has none (EPSG:n, WKT, PROJ or a .prj file), or 'local' for local metres");
    sub->add_option("--target-crs", g.target_crs,
                    "reproject the DEM to this projected CRS in metres (needed for a DEM in degrees), e.g. EPSG:32653");
    sub->add_option("--still-water-level", g.still_water_level,
                    "the DEM's value at still water in its vertical datum [m]: z = DEM - this")
        ->capture_default_str();
    sub->add_option("--extent", *extent, "keep only x_min,x_max,y_min,y_max [m, in the scene's CRS]")->expected(4)->delimiter(',');
    sub->add_option("--nodata-fill", g.nodata_fill, "elevation for the DEM's nodata cells [m above still water] (else an error)");
    sub->add_option("--buildings", g.buildings,
                    "building footprints (polygons: GeoJSON, shapefile, GeoPackage, ...), burnt into the building mask "
                    "instead of the features file's building rule");
    sub->add_option("--buildings-layer", g.buildings_layer, "layer of --buildings (default: the first)");
    sub->add_option("--building-height-field", g.building_height_field,
                    "attribute of --buildings with the height above ground [m]: z becomes the footprint's lowest ground + height");
    sub->add_option("--building-height", g.building_height, "height above ground [m] of footprints without a height value");
    sub->add_option("--manning-raster", g.manning_raster,
                    "raster of Manning n, or of land-use codes with --manning-classes (any CRS; resampled onto the scene)");
    sub->add_option("--manning-classes", g.manning_classes, "CSV 'class,n': the Manning n of each land-use code");
    sub->add_option("--manning-polygons", g.manning_polygons, "polygons with a Manning n attribute (win over the raster)");
    sub->add_option("--manning-field", g.manning_field, "the n attribute of --manning-polygons")->capture_default_str();
    add_config_option(sub);
    sub->callback([def, out, extent, command_line] {
        const OutputGuard guard({{"--out", *out}}, {{"--dem", def->dem_path}, {"--features", def->features_path}});
        if (!extent->empty()) def->gis.extent = std::array<double, 4>{(*extent)[0], (*extent)[1], (*extent)[2], (*extent)[3]};
        const Scene s = import_scene(*def);
        write_scene(*out, s, command_line);
        std::size_t roofs = 0;
        for (auto b : s.building) roofs += std::size_t(b);
        std::printf("scene: %s (%d x %d cells of %.4g m; %zu building cells; %zu points, %zu sections, %zu regions%s)\n",
                    out->c_str(), s.grid.nx, s.grid.ny, def->resolution, roofs, s.points.size(), s.sections.size(),
                    s.regions.size(), s.crs.empty() ? "" : ("; CRS " + s.crs.name()).c_str());
    });
}

void register_boundary_generate(CLI::App* boundary) {
    auto def = std::make_shared<BoundaryGenDef>();
    auto dir = std::make_shared<std::string>();
    CLI::App* sub = boundary->add_subcommand(
        "generate",
        "Write synthetic WG1 water-level records (CSV time,eta in s, m) wg1_r00.csv ... for the west boundary: "
        "one smooth leading wave (peak at the end of pumping, then return flow) plus smooth departures with "
        "ensemble std --spread; deterministic from --seed. Prints a summary.");
    sub->add_option("--out-dir", *dir, "directory for the CSV records")->required();
    sub->add_option("--count", def->count, "number of realisations")->capture_default_str()->check(in_range(Range::count(1, 1e5)));
    sub->add_option("--seed", def->seed, "seed of the departures")->capture_default_str();
    sub->add_option("--duration", def->duration, "record length [s]")->capture_default_str()->check(in_range(Range::positive("s")));
    sub->add_option("--dt", def->dt, "sample interval [s]")->capture_default_str()->check(in_range(Range::positive("s")));
    sub->add_option("--peak", def->peak, "mean level at the end of pumping [m]")
        ->capture_default_str()
        ->check(in_range(Range::any("m")));
    sub->add_option("--spread", def->spread, "ensemble standard deviation of the departures [m]")
        ->capture_default_str()
        ->check(in_range(Range::non_negative("m")));
    sub->add_option("--pump-end", def->pump_end, "end of pumping [s]")
        ->capture_default_str()
        ->check(in_range(Range::non_negative("s")));
    sub->add_option("--return-time", def->return_time, "relaxation time of the return flow [s]")
        ->capture_default_str()
        ->check(in_range(Range::positive("s")));
    auto scale = std::make_shared<double>(1.0);
    sub->add_option("--froude-scale", *scale,
                    "write the records at this many times the flume's scale (times x sqrt, levels x; 250: Kainan itself); "
                    "the other options stay in flume units")
        ->capture_default_str()
        ->check(in_range(Range::positive().up_to(1e4)));
    add_config_option(sub);
    auto allow_large = std::make_shared<bool>(false);
    sub->add_flag("--allow-large-run", *allow_large,
                  "write the records even when their samples pass the bound flotsam stops at (docs/reliability.md)");
    sub->callback([def, dir, scale, allow_large] {
        // The records' size before anything is computed: count x (duration / dt + 1)
        // samples (Froude scaling stretches duration and dt alike).
        const double samples = double(def->count) * (def->duration / def->dt + 1.0);
        const std::string span = number_text(def->count) + " records of " + number_text(def->duration) + " s every " +
                                 number_text(def->dt) + " s";
        check_work("--dt", span, samples, max_boundary_samples, "samples", *allow_large);
        check_allocation("--dt", span, samples, 3.0 * sizeof(double), "samples");
        // Levels a flume or a coast can have, after scaling: no sea is 11 km higher than still water.
        if (!(std::fabs(def->peak * *scale) <= 11000.0))
            fail("--peak", number_text(def->peak) + " m",
                 "x --froude-scale " + number_text(*scale) + " is a level of " + number_text(def->peak * *scale) +
                     " m, beyond the 11 km of any ocean's depth");
        std::vector<NamedPath> outputs;
        for (const auto& p : boundary_record_paths(*dir, def->count)) outputs.push_back({"--out-dir", p});
        const OutputGuard guard(outputs, {});
        auto records = generate_boundary_records(*def);
        if (*scale != 1.0) froude_scale(records, *scale);
        const auto paths = write_boundary_records(*dir, records);
        const BoundarySummary s = summarise_boundary(records, 30.0 * std::sqrt(*scale));
        std::printf("boundary: %zu records in %s (%s ... %s)\n", paths.size(), dir->c_str(), paths.front().c_str(),
                    paths.back().c_str());
        std::printf(
            "boundary summary: max ensemble mean %.4f m at %.1f s; ensemble std over t >= %.0f s: min %.3f mm, mean %.3f mm, max "
            "%.3f mm\n",
            s.max_mean, s.time_of_max, s.std_from, 1e3 * s.std_min, 1e3 * s.std_mean, 1e3 * s.std_max);
    });
}

}  // namespace

void register_data_commands(CLI::App& app, const std::string& command_line) {
    CLI::App* scene = app.add_subcommand("scene", "Scenes: generate the synthetic analogue or import a user DEM");
    scene->require_subcommand(1);
    register_scene_generate(scene, command_line);
    register_scene_import(scene, command_line);
    CLI::App* boundary = app.add_subcommand("boundary", "West-boundary water-level records (WG1)");
    boundary->require_subcommand(1);
    register_boundary_generate(boundary);
}

}  // namespace flotsam
