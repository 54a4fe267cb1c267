// GIS out: the hazard maps as Cloud-Optimised GeoTIFF and the debris tracks
// as lines in a vector file, in the scene's CRS, so a planner opens them in QGIS as they
// are. Reads the files flotsam writes (statistics, flow, trajectory or sweep files) by
// their variable names (formats/stats_file.hpp, flow_file.hpp, trajectory_file.hpp).
//
// Everything is read and checked first (stats_maps, flow_maps, read_tracks,
// read_buildings, the check_only modes), the files against each other too, and only then
// written (write_cog, write_tracks, write_buildings, ...): a refused export writes nothing.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "common/cf.hpp"
#include "common/grid.hpp"
#include "formats/trajectory_file.hpp"
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
// (0: not known), its scene_buildings_sha256 (formats/scene.hpp; "" for files written
// before it), its CRS, and where its positions lie (`extent`: x_min, x_max, y_min, y_max
// [m] of its grid; empty for tracks). `flotsam export` refuses to combine files of
// different scenes.
struct SceneOf {
    std::string path;
    double cell = 0.0;
    std::string fingerprint;
    cf::GridMapping crs;
    std::vector<double> extent;
};

// The maps of a statistics file (flotsam stats; read through stats_file::open_checked):
// pass probability and largest debris speed per group (body and model variant) and over
// all trajectories. A probability map without a value is a named error.
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

// What the tracks layer says of each trajectory besides its file's columns.
struct TrackSummary {
    double t_start = 0.0, t_end = 0.0;  // first and last sample [s]
    double path_length = 0.0;           // along its samples [m]
    double max_speed = 0.0;             // largest |(u, v)| [m s-1]; 0 when the file has no speeds
};
TrackSummary track_summary(const std::vector<double>& time, const debris::Track& track);

// The tracks of a trajectory or sweep file, read and checked (formats/trajectory_file.hpp,
// read_trajectory_table; a sweep file's
// member table against its tables, sweep::read_sweep_tables), with their summaries and
// each track's `source` (the GIS feature its body came from, else the body).
struct TrackLayer {
    debris::TrajectoryTable table;
    std::vector<TrackSummary> summaries;  // one per track
};
TrackLayer read_tracks(const std::string& trajectory_path, SceneOf* scene = nullptr);
// Writes one line per trajectory (its samples in time order) with the per-trajectory
// variables as attributes, plus t_start, t_end, path_length and max_speed, styled by
// source. The format follows the extension: .gpkg (GeoPackage), .geojson/.json (GeoJSON),
// .shp (shapefile). Returns the number of lines. Atomic as above.
std::size_t write_tracks(const TrackLayer& tracks, const std::string& out_path);
// The vector format of an output path's extension ("GPKG", ...); a named error for others.
const char* vector_driver_of(const std::string& out_path);

// The scene's buildings with the impact statistics of a statistics file over all
// trajectories (formats/stats_file.hpp: building_*_all), read and checked: the statistics
// must come from this scene (scene_buildings_sha256, their map grid the scene's, its CRS).
struct BuildingLayer {
    std::string scene_path;
    Grid grid;                                // the scene's
    cf::GridMapping crs;                      // the scene's
    std::vector<std::int32_t> ids;            // building_id per scene cell (0: none)
    std::vector<int> stat_ids;                // building_id of each statistics row
    std::vector<std::vector<double>> values;  // the nine statistics (hit probability ... largest force) per row
};
BuildingLayer read_buildings(const std::string& scene_path, const std::string& stats_path);
// As a GeoPackage layer `buildings`: one (multi)polygon per building_id, the union of its
// cells, in the scene's CRS, with its id, cells, area and hit_probability,
// first_hit_time_s, impacts, speed_median/p90/max_m_s, force_median/p90/max_N (null where
// never hit). Returns the number of buildings. Atomic as above.
std::size_t write_buildings(const BuildingLayer& buildings, const std::string& out_path);

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
