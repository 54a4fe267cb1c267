// GIS out: the hazard maps as Cloud-Optimised GeoTIFF and the debris tracks
// as lines in a vector file, in the scene's CRS, so a planner opens them in QGIS as they
// are. Reads the files flotsam writes (statistics, flow, trajectory or sweep files) by
// their variable names (formats/stats_file.hpp, flow_file.hpp, trajectory_file.hpp).
#pragma once
#include <string>
#include <vector>

#include "common/cf.hpp"
#include "common/grid.hpp"

namespace flotsam::gis {

// One map on a flotsam grid: values row-major with x fastest and the southern row first
// (as in every flotsam file); NaN where the map has no value (nodata in the GeoTIFF).
struct MapLayer {
    std::string name;       // file stem and band description, e.g. "pass_probability_FD_LC-MC"
    std::string long_name;  // what it is, with its group
    std::string units;      // UDUNITS, e.g. "m s-1"; "1" for a fraction
    std::vector<float> values;
};

// Writes `layer` as a Cloud-Optimised GeoTIFF (north-up, Float32, NaN nodata, DEFLATE,
// internal tiles and overviews) on grid `g` in `crs` (none: local metres, said in the
// file's metadata). Atomic: <path>.part, then renamed. `source` goes into the metadata.
void write_cog(const std::string& path, const Grid& g, const cf::GridMapping& crs, const MapLayer& layer,
               const std::string& source);

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

// The maps of one or more flow files of one scene: maximum depth, maximum speed, arrival
// time. Several flows (an ensemble) give their envelope: the largest depth and speed and
// the earliest arrival of any flow, each cell on its own. The flows must share the grid,
// the bed, the CRS and (where recorded) the building mask; a missing depth or speed,
// a negative one, or an arrival outside the run is a named error. Units other than m, s
// and m s-1 are converted (or refused by name).
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

// File name part for a group label: letters, digits, '-', '_' kept, '+' becomes '-'.
std::string file_safe(const std::string& label);

}  // namespace flotsam::gis
