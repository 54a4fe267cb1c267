// The statistics file: what `flotsam stats` writes from a sweep (sweep/sweep_stats.hpp)
// and `flotsam export` and the charts (pipelines/stats_file.py holds the same names) read.
// One CF-1.11 NetCDF file, flotsam_file_kind "stats"; what each statistic means is in
// docs/sweep.md. A group is one body with one model variant.
//
//   group_*, param_set_*, param_members     the groups and the sweep's parameter sets
//   section_*, region_name                  the scene's cross-sections and regions
//   passage_*[_by_param](group, [param_set,] section)
//                                           first passages: count, position and speed
//                                           summaries, speed density on `speed`
//   member_*(member[, section])             per trajectory: what it is, its passages, its
//                                           yaw after motion start and from the run's
//                                           start, its region at arrival_time_s
//   yaw_bin(yaw_bin), *_histogram(group, yaw_bin)   yaw histograms
//   max_rotation_from_start_*(group), rotation_direction_correlation(group)
//   region_count[_by_param](group, [param_set,] region)
//   time(time), distance_*(group, param_set, time), relative_error  R(t)
//   building_id(building), building_*(group, building) and building_*_all(building)
//                                           impacts on the scene's buildings: hit
//                                           probability, first hit, speed and force
//   x(x), y(y), pass_probability, max_debris_speed (group, y, x) and *_all (y, x): maps
//                                           that name the scene's CF grid mapping (crs)
//                                           when it has one
//   global attributes                       the inputs and every setting (`attribute`)
// No time stamps anywhere: the same sweep and settings give the same bytes.
#pragma once
#include <string>
#include <vector>

#include "common/checks.hpp"
#include "common/grid.hpp"
#include "common/netcdf.hpp"

namespace flotsam::stats_file {

inline constexpr const char* kind = "stats";  // flotsam_file_kind (common/cf.hpp)

// The dimensions, in the order the file defines them.
namespace dim {
inline constexpr const char* group = "group";
inline constexpr const char* param_set = "param_set";
inline constexpr const char* section = "section";
inline constexpr const char* region = "region";
inline constexpr const char* speed = "speed";  // the axis of the speed densities
inline constexpr const char* yaw_bin = "yaw_bin";
inline constexpr const char* bnds = "bnds";  // the two edges of a yaw bin
inline constexpr const char* time = "time";
inline constexpr const char* member = "member";  // one trajectory of the sweep
inline constexpr const char* building = "building";  // one building of the scene (building_id)
inline constexpr const char* x = "x";            // map columns
inline constexpr const char* y = "y";            // map rows
}  // namespace dim
const std::vector<std::string>& dimension_names();

// A variable of the file, as the writer defines it. Strings (NC_CHAR) add a string-length
// dimension of their own after `dims`.
struct Variable {
    const char* name;
    nc_type type;
    std::vector<const char*> dims;  // names in `dim`, slowest first
    const char* units;              // UDUNITS; "" for counts, indices and strings
    const char* long_name;
    bool fill;  // missing values are stored as the fill value (common/cf.hpp)
};

// The groups, parameter sets, sections and regions. The parameter-set table
// (param_set_label, param_set_is_control, param_set_<parameter>) is that of the sweep
// file, written by the same code (sweep/sweep_file.hpp).
extern const Variable group_body, group_variant, group_members;
inline constexpr const char* param_set_label = "param_set_label";
inline constexpr const char* param_set_is_control = "param_set_is_control";
inline constexpr const char* param_set_value_prefix = "param_set_";  // + the parameter's name
extern const Variable param_members;
extern const Variable section_name, section_x, section_y_min, section_y_max;
extern const Variable region_name;

// First passages at the sections: the same summaries per group over (group, section) and
// per parameter set over (group, param_set, section), names ending in "_by_param".
struct PassageVariables {
    Variable count;                                // trajectories passing
    Variable y_mean, y_median, y_std;              // passage position [m]
    Variable speed_mean, speed_median, speed_std;  // passage speed [m s-1]
    Variable speed_bandwidth;                      // of the kernel density [m s-1]
    Variable speed_kde;                            // density over ..., speed [s m-1]
};
extern const PassageVariables passage, passage_by_param;
extern const Variable speed;                                                        // [m s-1]
extern const Variable member_passage_time, member_passage_y, member_passage_speed;  // (member, section)

// Yaw histograms after motion starts, and their bins.
extern const Variable yaw_bin, yaw_bin_bounds;  // yaw_bin names yaw_bin_bounds as its "bounds"
extern const Variable max_rotation_histogram, max_yaw_to_motion_histogram;

// What each member is.
extern const Variable member_id, member_group, member_param_set, member_flow;
// Each member's motion start and its yaw after it.
extern const Variable member_motion_start, member_max_rotation, member_max_yaw_to_motion, member_motion_direction;

// The paper's Fig. 16, from the run's start: per member, then per group.
extern const Variable member_max_rotation_from_start, member_movement_direction;
extern const Variable max_rotation_from_start_histogram, max_rotation_from_start_count;
extern const Variable max_rotation_from_start_median, max_rotation_from_start_mean, max_rotation_from_start_min,
    max_rotation_from_start_max;
extern const Variable rotation_direction_correlation;

// Regions at the arrival time.
extern const Variable member_region, region_count, region_count_by_param;

// Distance from the start and R(t), on the sweep's output times.
inline constexpr const char* time = "time";  // [s] (common/cf.hpp, def_time)
extern const Variable distance_mean, distance_std, relative_error;

// Impacts on the scene's buildings (formats/impact_file.hpp), per (group, building) and
// over all trajectories per building (the same names with "_all").
extern const Variable building_id;
struct BuildingVariables {
    Variable hit_probability;                          // share of the trajectories that hit it at least once
    Variable first_hit_time;                           // earliest impact [s]
    Variable impact_count;                             // impacts
    Variable speed_median, speed_p90, speed_max;       // impact speed [m s-1]
    Variable force_median, force_p90, force_max;       // impact force [N]
};
extern const BuildingVariables building, building_all;

// The maps, on the map cells' centres x and y [m] (common/cf.hpp, def_xy).
inline constexpr const char* x = "x";
inline constexpr const char* y = "y";
extern const Variable pass_probability, max_debris_speed, pass_probability_all, max_debris_speed_all;

// Every Variable above, in the order of the file.
const std::vector<const Variable*>& variables();
// Every variable name above, in the order of the file (without the grid mapping and the
// per-parameter param_set_<parameter> columns, which depend on the scene and the sweep).
const std::vector<std::string>& variable_names();

// The global attributes, after Conventions and flotsam_file_kind.
namespace attribute {
inline constexpr const char* title = "title";
inline constexpr const char* source = "source";
inline constexpr const char* sweep_file = "sweep_file";
inline constexpr const char* scene_file = "scene_file";
inline constexpr const char* scene_buildings_sha256 = "scene_buildings_sha256";  // formats/scene.hpp
inline constexpr const char* history = "history";
inline constexpr const char* yaw_window = "yaw_window_s";              // [s]
inline constexpr const char* yaw_min_speed = "yaw_min_speed_m_s";      // [m s-1]
inline constexpr const char* motion_threshold = "motion_threshold_m";  // [m]
inline constexpr const char* arrival_time = "arrival_time_s";          // [s]
inline constexpr const char* r_min_distance = "r_min_distance_m";      // [m]
inline constexpr const char* kde_bandwidth_rule = "kde_bandwidth_rule";
inline constexpr const char* kde_floor = "kde_floor_m_s";              // [m s-1]
inline constexpr const char* control_param_set = "control_param_set";  // index; -1: none
inline constexpr const char* map_coarsen = "map_coarsen";              // scene cells per map cell along a side
}  // namespace attribute
const std::vector<std::string>& attribute_names();

// The tables `flotsam stats --csv DIR` writes into DIR, in order.
namespace csv {
inline constexpr const char* sections = "sections.csv";
inline constexpr const char* speed_kde = "speed_kde.csv";
inline constexpr const char* yaw_histogram = "yaw_histogram.csv";
inline constexpr const char* rotation_from_start = "rotation_from_start.csv";
inline constexpr const char* regions = "regions.csv";
inline constexpr const char* distance = "distance.csv";
inline constexpr const char* members = "members.csv";
inline constexpr const char* buildings = "buildings.csv";
}  // namespace csv
// The paths of those tables in `dir`.
std::vector<std::string> csv_paths(const std::string& dir);

// ---- reading, checked ----

// The values a statistic keeps, in its unit: fractions of trajectories in [0, 1], counts
// from 0 (member_region from -1, "none"), speeds and forces from 0, a correlation in
// [-1, 1], positions and distances within 1e8 m (spreads from 0), angles within 1e9
// degrees; any finite time.
Range range_of(const Variable& v);

// Opens a statistics file and checks it whole before anything reads it: its kind, every
// variable of the schema it holds on the schema's dimensions, in a unit that converts to
// the schema's (common/units.hpp), every value finite, or the fill value where the
// variable stores missing values, and within range_of(); the map axes x and y uniform.
// Errors name the file, the variable and the value's place. `option` names where the file
// was given ("--stats").
nc::File open_checked(const std::string& path, const std::string& option);
// A variable of a file from open_checked, in the schema's units; missing values NaN.
std::vector<double> read_values(const nc::File& f, const Variable& v);
// The map grid: the cell centres x and y [m].
Grid map_grid(const nc::File& f);

}  // namespace flotsam::stats_file
