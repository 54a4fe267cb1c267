// GIS out: the hazard maps as Cloud-Optimised GeoTIFF and the debris tracks
// as lines in a vector file, in the scene's CRS, so a planner opens them in QGIS as they
// are. Reads the files flotsam writes (statistics, flow, trajectory or sweep files) by
// their variable names (formats/stats_file.hpp, flow_file.hpp, trajectory_file.hpp).
#pragma once
#include <string>
#include <vector>

#include "common/cf.hpp"
#include "common/grid.hpp"
#include "export/qgis_project.hpp"
#include "export/qgis_style.hpp"

namespace flotsam::gis {

// One map on a flotsam grid: values row-major with x fastest and the southern row first
// (as in every flotsam file); NaN where the map has no value (nodata in the GeoTIFF):
// "nothing" (a dry cell, a cell no body passes) is no value, never 0.
struct MapLayer {
    std::string name;       // file stem and band description, e.g. "pass_probability_FD_LC-MC"
    std::string long_name;  // what it is, with its group
    std::string units;      // UDUNITS, e.g. "m s-1"; "1" for a fraction
    std::vector<float> values;
    std::string title;        // short name in a QGIS legend, e.g. "pass probability FD LC+MC"
    qgis::RasterStyle style;  // its colours over a fixed physical range (none: QGIS's default grey)
};

// Writes `layer` as a Cloud-Optimised GeoTIFF (north-up, Float32, NaN nodata, DEFLATE,
// internal tiles, at least one overview, the band's statistics) on grid `g` in `crs`
// (none: local metres, said in the file's metadata), and its style as <stem>.qml beside
// it (QGIS applies it when it opens the GeoTIFF). Atomic: <path>.part, then renamed.
// `source` goes into the metadata.
void write_cog(const std::string& path, const Grid& g, const cf::GridMapping& crs, const MapLayer& layer,
               const std::string& source);

// Crops `maps` on `g` to the cells inside `window` (the flow's output window, where bodies
// can move) and any cell outside it that holds a value; `g` becomes the cropped grid.
void crop_maps(std::vector<MapLayer>& maps, Grid& g, const Grid& window);

// The scene an exported file was computed on, as far as the file says: its cell size
// (0: not known) and its scene_buildings_sha256 (formats/scene.hpp; "" for files written
// before it).
// `flotsam export` refuses to combine files of different scenes.
struct SceneOf {
    std::string path;
    double cell = 0.0;
    std::string fingerprint;
    cf::GridMapping crs;
};

// The maps of a statistics file (flotsam stats): pass probability and largest debris
// speed per group (body and model variant) and over all trajectories. Probabilities
// outside [0, 1], negative speeds and maps without a value are named errors.
std::vector<MapLayer> stats_maps(const std::string& stats_path, Grid& grid, cf::GridMapping& crs, SceneOf* scene = nullptr);

// The maps of one or more flow files of one scene: maximum depth, the onshore part of it
// (inundation depth: cells whose bed, buildings included, stands above still water),
// maximum speed, arrival time; cells never flooded (depth never above the flow's
// flood_depth) have no value. Several flows (an ensemble) give their envelope: the largest
// depth and speed and the earliest arrival of any flow, each cell on its own. The flows
// must share the grid, the bed, the CRS and (where recorded) the building mask; a missing
// depth or speed, a negative one, or an arrival outside the run is a named error. Units
// other than m, s and m s-1 are converted (or refused by name).
std::vector<MapLayer> flow_maps(const std::vector<std::string>& flow_paths, Grid& grid, cf::GridMapping& crs,
                                SceneOf* scene = nullptr);

// Writes the tracks of a trajectory or sweep file as one line per trajectory (its
// samples in time order, fill values left out) with the per-trajectory variables as
// attributes, plus start and end time, path length and largest speed. The format
// follows the extension: .gpkg (GeoPackage), .geojson/.json (GeoJSON), .shp
// (shapefile). Returns the number of lines. Atomic as above.
// The file is checked first: its kind, its track variables on (trajectory, time), its
// per-trajectory variables on trajectory, finite positions, increasing times; a sweep file
// goes through sweep::read_sweep_file.
// With `check_only`, it stops after the checks (nothing written) and returns the number of
// trajectories.
std::size_t write_tracks(const std::string& trajectory_path, const std::string& out_path, SceneOf* scene = nullptr,
                         bool check_only = false);

// The scene's buildings as a GeoPackage layer `buildings`: one (multi)polygon per
// building_id, the union of its cells, in the scene's CRS, with its id, cells, area and
// the impact statistics over all trajectories of `stats_path` (flotsam stats; formats/
// stats_file.hpp: building_*_all): hit_probability, first_hit_time_s, impacts,
// speed_median/p90/max_m_s, force_median/p90/max_N (null where never hit). The statistics
// must come from this scene (scene_buildings_sha256). Returns the number of buildings.
// Atomic as above.
std::size_t write_building_footprints(const std::string& scene_path, const std::string& stats_path, const std::string& out_path);

// The debris sources of a study (the vector file given to `flotsam debris --sources` or a
// sweep's [[sources]]): every feature of every layer, carried into `crs` (the scene's),
// as a GeoPackage with layers `source_areas` (yards) and `source_points` (single bodies),
// each feature with its `layer`, `feature` id, `type` and `count`. Returns the features.
// With `check_only`, it stops after reading and carrying them (nothing written).
std::size_t write_sources(const std::string& sources_path, const cf::GridMapping& crs, const std::string& out_path,
                          bool check_only = false);

// The design standard's hazard regions (pipelines/hazard_region.py's hazard_regions.nc:
// region_inflow and region_outflow per source on the scene grid) as polygons in a
// GeoPackage layer `hazard_regions` with `source`, `flow` ("inflow" or "return flow"),
// `cells` and `area_m2`. Returns the polygons. With `check_only`, it stops after reading
// (nothing written) and returns the regions' CRS in `crs`.
std::size_t write_hazard_regions(const std::string& regions_path, const std::string& out_path, bool check_only = false,
                                 cf::GridMapping* crs = nullptr);

// The scene's named features as a GeoPackage in its CRS: layers `starts` (debris starts,
// with their heading), `gauges`, `sections` (the passage lines) and `regions` (the
// arrival-count polygons), those the scene has, each feature with its `name`. Returns the
// features (0: none, nothing written).
std::size_t write_scene_features(const std::string& scene_path, const std::string& out_path);

// A flow file as a time-aware mesh layer of a QGIS project: water depth in colour over
// `depth_top` [m], the velocity as arrows, its times on the temporal controller.
qgis::ProjectLayer flow_mesh_layer(const std::string& flow_path, double depth_top);

// File name part for a group label: letters, digits, '-', '_' kept, '+' becomes '-'.
std::string file_safe(const std::string& label);

}  // namespace flotsam::gis
