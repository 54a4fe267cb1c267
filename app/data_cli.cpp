// Command-line surface of the data stage: `scene generate`, `scene import`,
// `boundary generate`, each command's options from a settings table (common/settings.hpp).
#include <cmath>
#include <cstdio>
#include <string>

#include "app/commands.hpp"
#include "app/settings_cli.hpp"
#include "common/checks.hpp"
#include "common/error.hpp"
#include "common/output_lock.hpp"
#include "data/boundary_generator.hpp"
#include "data/dem_import.hpp"
#include "data/scene_generator.hpp"
#include "formats/scene.hpp"

namespace flotsam {

namespace {

// `scene generate`: the generator's settings and where the scene goes.
struct SceneGenerateOptions {
    SceneGenDef def;
    std::string out;
};

const Settings<SceneGenerateOptions>& scene_generate_settings() {
    using O = SceneGenerateOptions;
    static const Settings<O> table = {
        {"resolution", "m", "grid spacing [m], e.g. 0.01, 0.02, 0.04", Range::positive("m").up_to(100.0),
         member_of<&O::def, &SceneGenDef::resolution>()},
        {"seed", "1", "seed of the building layout", Range(), member_of<&O::def, &SceneGenDef::seed>(), {.unchecked = true}},
        {"out", "", "output scene file (NetCDF)", Range(), &O::out, {.required = true, .no_default = true}},
        {"lot-build-probability", "1", "chance that a city lot holds a building", Range::closed(0.0, 1.0),
         member_of<&O::def, &SceneGenDef::lot_build_probability>()},
    };
    return table;
}

void register_scene_generate(CLI::App* scene, const std::string& command_line) {
    auto o = std::make_shared<SceneGenerateOptions>();
    CLI::App* sub =
        scene->add_subcommand("generate",
                              "Write the synthetic analogue of the Kainan port-city flume (SCENE.md) at any grid spacing; "
                              "deterministic from --seed; marked synthetic in its metadata");
    add_setting_options(sub, scene_generate_settings(), *o);
    add_config_option(sub);
    sub->callback([o, command_line] {
        const OutputGuard guard({{"--out", o->out}}, {});
        const GeneratedScene g = generate_scene(o->def);
        write_scene(o->out, g.scene, command_line);
        std::printf("scene: %s (%d x %d cells of %.4g m, synthetic)\n", o->out.c_str(), g.scene.grid.nx, g.scene.grid.ny,
                    o->def.resolution);
    });
}

// `scene import`: the DEM, its features and GIS inputs, and where the scene goes.
struct SceneImportOptions {
    ImportDef def;
    std::string out;
    std::vector<double> extent;  // x_min, x_max, y_min, y_max [m]: def.gis.extent when given
};

const Settings<SceneImportOptions>& scene_import_settings() {
    using O = SceneImportOptions;
    const OptionForm path{.no_default = true};  // a path or a name, none by default
    static const Settings<O> table = {
        {"dem",
         "",
         "DEM file (GeoTIFF, .asc, NetCDF, or anything GDAL reads)",
         Range(),
         member_of<&O::def, &ImportDef::dem_path>(),
         {.required = true, .no_default = true}},
        {"features", "", "features TOML file", Range(), member_of<&O::def, &ImportDef::features_path>(), path},
        {"resolution", "m", "grid spacing of the scene", Range::positive("m").up_to(1e5),
         member_of<&O::def, &ImportDef::resolution>()},
        {"out", "", "output scene file (NetCDF)", Range(), &O::out, {.required = true, .no_default = true}},
        {"crs", "", "the DEM's CRS when its file has none (EPSG:n, WKT, PROJ or a .prj file), or 'local' for local metres", Range(),
         member_of<&O::def, &ImportDef::gis, &GisImportDef::assign_crs>(), path},
        {"target-crs", "", "reproject the DEM to this projected CRS in metres (needed for a DEM in degrees), e.g. EPSG:32653",
         Range(), member_of<&O::def, &ImportDef::gis, &GisImportDef::target_crs>(), path},
        {"still-water-level",
         "m",
         "the DEM's value at still water in its vertical datum [m]: z = DEM - this",
         Range(),
         member_of<&O::def, &ImportDef::gis, &GisImportDef::still_water_level>(),
         {.unchecked = true}},
        {"extent",
         "m",
         "keep only x_min,x_max,y_min,y_max [m, in the scene's CRS]",
         Range(),
         &O::extent,
         {.no_default = true, .unchecked = true, .items = 4}},
        {"nodata-fill",
         "m",
         "elevation for the DEM's nodata cells [m above still water] (else an error)",
         Range(),
         member_of<&O::def, &ImportDef::gis, &GisImportDef::nodata_fill>(),
         {.no_default = true, .unchecked = true}},
        {"buildings", "",
         "building footprints (polygons: GeoJSON, shapefile, GeoPackage, ...), burnt into the building mask instead of the "
         "features file's building rule",
         Range(), member_of<&O::def, &ImportDef::gis, &GisImportDef::buildings>(), path},
        {"buildings-layer", "", "layer of --buildings (default: the first)", Range(),
         member_of<&O::def, &ImportDef::gis, &GisImportDef::buildings_layer>(), path},
        {"building-height-field", "",
         "attribute of --buildings with the height above ground [m]: z becomes the footprint's lowest ground + height", Range(),
         member_of<&O::def, &ImportDef::gis, &GisImportDef::building_height_field>(), path},
        {"building-height",
         "m",
         "height above ground [m] of footprints without a height value",
         Range(),
         member_of<&O::def, &ImportDef::gis, &GisImportDef::building_height>(),
         {.no_default = true, .unchecked = true}},
        {"manning-raster", "",
         "raster of Manning n, or of land-use codes with --manning-classes (any CRS; resampled onto the scene)", Range(),
         member_of<&O::def, &ImportDef::gis, &GisImportDef::manning_raster>(), path},
        {"manning-classes", "", "CSV 'class,n': the Manning n of each land-use code", Range(),
         member_of<&O::def, &ImportDef::gis, &GisImportDef::manning_classes>(), path},
        {"manning-polygons", "", "polygons with a Manning n attribute (win over the raster)", Range(),
         member_of<&O::def, &ImportDef::gis, &GisImportDef::manning_polygons>(), path},
        {"manning-field", "", "the n attribute of --manning-polygons", Range(),
         member_of<&O::def, &ImportDef::gis, &GisImportDef::manning_field>()},
    };
    return table;
}

void register_scene_import(CLI::App* scene, const std::string& command_line) {
    auto o = std::make_shared<SceneImportOptions>();
    CLI::App* sub = scene->add_subcommand(
        "import",
        "Import a user DEM as a scene: any raster GDAL reads (GeoTIFF, ESRI ASCII grid, NetCDF, ...) in a projected CRS "
        "in metres (or local metres), resampled to --resolution (cell-area average when coarsening, bilinear when "
        "refining), with points, sections, regions, Manning rules and a building rule from --features (TOML; see "
        "docs/scene.md), building footprints from a vector file, and Manning n from a land-use raster or polygons. "
        "Without --features, a DEM with the Kainan extent gets the Kainan defaults; any other DEM gets no features "
        "and no Manning field.");
    add_setting_options(sub, scene_import_settings(), *o);
    add_config_option(sub);
    sub->callback([o, command_line] {
        ImportDef& def = o->def;
        const GisImportDef& gis = def.gis;
        const auto file = [](const std::string& crs) { return file_type_of(crs).empty() ? std::string() : crs; };  // a .prj, not "EPSG:n"
        const OutputGuard guard({{"--out", o->out}},
                                {{"--dem", def.dem_path, true},
                                 {"--features", def.features_path},
                                 {"--buildings", gis.buildings, true},
                                 {"--manning-raster", gis.manning_raster, true},
                                 {"--manning-classes", gis.manning_classes},
                                 {"--manning-polygons", gis.manning_polygons, true},
                                 {"--crs", file(gis.assign_crs)},
                                 {"--target-crs", file(gis.target_crs)}});
        if (!o->extent.empty()) def.gis.extent = std::array<double, 4>{o->extent[0], o->extent[1], o->extent[2], o->extent[3]};
        const Scene s = import_scene(def);
        write_scene(o->out, s, command_line);
        std::size_t roofs = 0;
        for (auto b : s.building) roofs += std::size_t(b);
        std::printf("scene: %s (%d x %d cells of %.4g m; %zu building cells; %zu points, %zu sections, %zu regions%s)\n",
                    o->out.c_str(), s.grid.nx, s.grid.ny, def.resolution, roofs, s.points.size(), s.sections.size(),
                    s.regions.size(), s.crs.empty() ? "" : ("; CRS " + s.crs.name()).c_str());
    });
}

// `boundary generate`: the records' settings, their scale, and where they go.
struct BoundaryGenerateOptions {
    BoundaryGenDef def;
    std::string out_dir;
    double froude_scale = 1.0;     // [-] written at this many times the flume's scale
    bool allow_large_run = false;  // write even past the bound on samples
};

const Settings<BoundaryGenerateOptions>& boundary_generate_settings() {
    using O = BoundaryGenerateOptions;
    static const Settings<O> table = {
        {"out-dir", "", "directory for the CSV records", Range(), &O::out_dir, {.required = true, .no_default = true}},
        {"count", "1", "number of realisations", Range::count(1, 1e5), member_of<&O::def, &BoundaryGenDef::count>()},
        {"seed", "1", "seed of the departures", Range(), member_of<&O::def, &BoundaryGenDef::seed>(), {.unchecked = true}},
        {"duration", "s", "record length", Range::positive("s"), member_of<&O::def, &BoundaryGenDef::duration>()},
        {"dt", "s", "sample interval", Range::positive("s"), member_of<&O::def, &BoundaryGenDef::dt>()},
        {"peak", "m", "mean level at the end of pumping", Range::any("m"), member_of<&O::def, &BoundaryGenDef::peak>()},
        {"spread", "m", "ensemble standard deviation of the departures", Range::non_negative("m"),
         member_of<&O::def, &BoundaryGenDef::spread>()},
        {"pump-end", "s", "end of pumping", Range::non_negative("s"), member_of<&O::def, &BoundaryGenDef::pump_end>()},
        {"return-time", "s", "relaxation time of the return flow", Range::positive("s"),
         member_of<&O::def, &BoundaryGenDef::return_time>()},
        {"froude-scale", "1",
         "write the records at this many times the flume's scale (times x sqrt, levels x; 250: Kainan itself); the other "
         "options stay in flume units",
         Range::positive().up_to(1e4), &O::froude_scale},
        {"allow-large-run",
         "",
         "write the records even when their samples pass the bound flotsam stops at (docs/reliability.md)",
         Range(),
         &O::allow_large_run,
         {.no_default = true}},
    };
    return table;
}

void register_boundary_generate(CLI::App* boundary) {
    auto o = std::make_shared<BoundaryGenerateOptions>();
    CLI::App* sub = boundary->add_subcommand(
        "generate",
        "Write synthetic WG1 water-level records (CSV time,eta in s, m) wg1_r00.csv ... for the west boundary: "
        "one smooth leading wave (peak at the end of pumping, then return flow) plus smooth departures with "
        "ensemble std --spread; deterministic from --seed. Prints a summary.");
    add_setting_options(sub, boundary_generate_settings(), *o);
    add_config_option(sub);
    sub->callback([o] {
        const BoundaryGenDef& def = o->def;
        const double scale = o->froude_scale;
        // The records' size before anything is computed: count x (duration / dt + 1)
        // samples (Froude scaling stretches duration and dt alike).
        const double samples = double(def.count) * (def.duration / def.dt + 1.0);
        const std::string span =
            number_text(def.count) + " records of " + number_text(def.duration) + " s every " + number_text(def.dt) + " s";
        check_work("--dt", span, samples, max_boundary_samples, "samples", o->allow_large_run);
        check_allocation("--dt", span, samples, 3.0 * sizeof(double), "samples");
        // Levels a flume or a coast can have, after scaling: no sea is 11 km higher than still water.
        if (!(std::fabs(def.peak * scale) <= 11000.0))
            fail("--peak", number_text(def.peak) + " m",
                 "x --froude-scale " + number_text(scale) + " is a level of " + number_text(def.peak * scale) +
                     " m, beyond the 11 km of any ocean's depth");
        std::vector<NamedPath> outputs;
        for (const auto& p : boundary_record_paths(o->out_dir, def.count)) outputs.push_back({"--out-dir", p});
        const OutputGuard guard(outputs, {});
        auto records = generate_boundary_records(def);
        if (scale != 1.0) froude_scale(records, scale);
        const auto paths = write_boundary_records(o->out_dir, records);
        const BoundarySummary s = summarise_boundary(records, 30.0 * std::sqrt(scale));
        std::printf("boundary: %zu records in %s (%s ... %s)\n", paths.size(), o->out_dir.c_str(), paths.front().c_str(),
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
