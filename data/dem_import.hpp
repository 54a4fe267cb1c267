// Importing a user DEM as a scene: NetCDF (x, y, z) or ESRI ASCII grid, resampled to
// the run's grid spacing, with points, sections, regions, Manning n and a building mask
// from a small TOML features file (or the Kainan defaults when the extent matches).
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "common/grid.hpp"
#include "data/gis_import.hpp"
#include "data/kainan_features.hpp"
#include "data/manning.hpp"
#include "formats/scene.hpp"

namespace flotsam {

// A DEM as read: elevation above still water on a uniform cell-centred grid.
struct Dem {
    Grid grid;
    std::vector<double> z;  // [m], j * nx + i, j = 0 the southern row
    std::string path;
    std::string title;    // the file's title attribute, if any
    cf::GridMapping crs;  // its CRS; empty: local metres
    Grid source_grid;     // the file's grid before --extent cropped it (nx = 0: not cropped)
};

// Reads `.asc` as an ESRI ASCII grid, anything else as NetCDF with variables x, y and
// z(y, x) (y may decrease; rows are then flipped). Errors name the file and the variable,
// header key or line.
Dem read_dem(const std::string& path);
// Any DEM: the two readers above when they apply (an ESRI grid, or a NetCDF with x, y, z)
// and `gis` asks for no reprojection, cropping or filling (the CRS then comes from a .prj
// beside the grid, the NetCDF's grid mapping, or --crs; none is local metres as before);
// everything else through GDAL (data/gis_import.hpp), where a CRS is required.
Dem read_dem(const std::string& path, const GisImportDef& gis, double resolution);
Dem read_ascii_grid(const std::string& path);

// How cells become buildings: z above the local ground by more than min_height, where
// local ground is the lowest max(z, 0) within `window` of the cell (so water next to a
// building counts as ground at still-water level); or, when min_elevation is set,
// simply z > min_elevation.
struct BuildingRule {
    double min_height = 0.03;             // [m] above local ground
    double window = 0.25;                 // half-width of the ground search square [m]
    std::optional<double> min_elevation;  // [m] above still water; replaces the above
};

// Everything a features file can set.
struct ImportFeatures {
    SceneFeatures features;
    std::vector<ManningRule> manning;  // empty: no manning_n field (the run's default applies)
    BuildingRule buildings;
    // [hydro]: recommended hydro settings (Scene::hydro_defaults), "key = value" lines.
    std::string hydro_defaults;
};

// The hydro options a scene may recommend: those whose defaults hold at the flume's
// scale only (docs/gis.md, "Any scale").
const std::vector<std::string>& scene_hydro_options();

// The Kainan defaults: kainan_features(KainanLayout::measured), kainan_manning(), kainan_hydro_defaults() and the
// default building rule.
ImportFeatures kainan_import_features();

// Reads a features TOML file. Tables it leaves out keep the values of `defaults`.
ImportFeatures read_import_features(const std::string& path, const ImportFeatures& defaults);

// What to import.
struct ImportDef {
    std::string dem_path;
    std::string features_path;  // empty: Kainan defaults when the DEM's extent matches, else none
    double resolution = 0.02;   // target grid spacing [m]
    GisImportDef gis;           // CRS, datum, nodata, footprints, land use (all optional)
};

Scene import_scene(const ImportDef& def);

// Building mask (0/1) of field z on grid g under `rule`.
std::vector<std::int8_t> building_mask(const Grid& g, const std::vector<double>& z, const BuildingRule& rule);

}  // namespace flotsam
