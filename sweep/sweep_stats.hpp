// The paper's statistics over a sweep, plus the maps it lacks. Grouped by body × model
// variant ("group"), and within a group by parameter set where that means something.
// Definitions (and every output variable) in docs/sweep.md; the per-trajectory pieces
// are the kernels of sweep/trajectory_kernels.hpp.
#pragma once
#include <string>
#include <vector>

#include "common/grid.hpp"
#include "formats/scene.hpp"
#include "sweep/sweep_file.hpp"

namespace flotsam::sweep {

// The lengths and speeds here hold for the paper's 0.25 m box; for another body each
// group's are scaled by Froude's law with its body length (trajectory_kernels.hpp,
// body_scale). The times (yaw_window, arrival_time) are the user's to set.
struct StatsDef {
    double yaw_window = 30.0;      // yaw statistics over this long after the start (and after motion starts) [s]
    double yaw_min_speed = 0.005;  // yaw against the motion only at samples at least this fast [m/s] (x sqrt(L/0.25 m))
    double yaw_bin_width = 10.0;   // histogram bins over [−180, 180] [degree]
    double arrival_time = 300.0;   // region counts at this time [s]
    double r_min_distance = 0.01;  // R(t) left undefined where the control's mean distance is below this [m] (x L/0.25 m)
    int kde_points = 128;          // points of the speed axis of the density estimates [-]
    double kde_floor = 1e-3;       // smallest bandwidth, used when passage speeds do not spread [m/s] (x sqrt(L/0.25 m))
    int map_coarsen = 1;           // map cell = this many scene cells along each side [-]
};
StatsDef default_stats_def();

// Statistics of the values at one cross-section (first passages).
struct SectionSummary {
    int count = 0;
    double y_mean = 0, y_median = 0, y_std = 0;              // passage position [m] (NaN: none)
    double speed_mean = 0, speed_median = 0, speed_std = 0;  // passage speed [m/s]
    double bandwidth = 0;                                    // KDE bandwidth [m/s]
    std::vector<double> kde;                                 // density on SweepStats::speed [s/m]
};

struct SweepStats {
    struct Group {
        std::string body;  // the body's name, or the GIS source "layer/fid" its bodies came from
        std::string variant;
        std::vector<int> members;  // indices into SweepResult::members
    };
    std::vector<Group> groups;
    std::vector<ParameterSet> params;
    int control = -1;  // index of the control parameter set (-1: none, R(t) undefined)
    std::vector<Section> sections;
    std::vector<std::string> regions;
    std::string scene_buildings_sha256;  // of the scene the statistics were computed on (formats/scene.hpp)

    // Per member (index into SweepResult::members); NaN where undefined.
    std::vector<int> member_group, member_id, member_param_set, member_flow;
    std::vector<double> motion_start, max_rotation, max_yaw_to_motion, motion_direction;  // [s], [degree] ×3
    std::vector<std::vector<double>> passage_time, passage_y, passage_speed;              // [member][section]
    std::vector<int> region_at_arrival;                                                   // region index, −1: none

    std::vector<double> speed;                                               // KDE axis [m/s]
    std::vector<std::vector<SectionSummary>> section;                        // [group][section]
    std::vector<std::vector<std::vector<SectionSummary>>> section_by_param;  // [group][param][section]

    std::vector<double> yaw_edges;                                 // bin edges [degree]
    std::vector<std::vector<int>> rotation_hist, yaw_motion_hist;  // [group][bin]

    // The paper's Fig. 16, over the first yaw_window seconds of the run (from the first
    // output time, whether or not the body moves yet): per member the largest rotation
    // from the initial heading and the direction of movement from the initial location.
    std::vector<double> max_rotation_from_start, movement_direction;  // [member] [degree]
    std::vector<std::vector<int>> rotation_from_start_hist;           // [group][bin]
    struct RotationSummary {
        int count = 0;                                  // members with a rotation
        double median = 0, mean = 0, min = 0, max = 0;  // of the largest rotation [degree]
        double direction_correlation = 0;               // Pearson r with the movement direction [-]
    };
    std::vector<RotationSummary> rotation_from_start;  // [group]

    std::vector<std::vector<int>> region_count;                        // [group][region]
    std::vector<std::vector<std::vector<int>>> region_count_by_param;  // [group][param][region]

    std::vector<double> time;                                                                   // [s]
    std::vector<std::vector<std::vector<double>>> distance_mean, distance_std, relative_error;  // [group][param][time]
    std::vector<std::vector<int>> param_members;                                                // [group][param]: members averaged

    // Impacts on the scene's buildings (formats/impact_file.hpp), per group and over all
    // trajectories; NaN where the building was not hit.
    struct BuildingSummary {
        double hit_probability = 0.0;               // share of the trajectories with an impact on it [-]
        double first_hit_time = 0.0;                // [s]
        int impacts = 0;                            // impacts on it
        double speed_median = 0, speed_p90 = 0, speed_max = 0;  // impact speed [m/s]
        double force_median = 0, force_p90 = 0, force_max = 0;  // impact force [N]
    };
    std::vector<std::int32_t> building_ids;                   // the scene's ids, increasing
    std::vector<std::vector<BuildingSummary>> building;       // [group][building]
    std::vector<BuildingSummary> building_all;                // [building]

    Grid map;                                                     // the map grid
    std::vector<std::vector<float>> pass_probability, max_speed;  // [group][cell]; max_speed NaN: never passed
    std::vector<float> pass_probability_all, max_speed_all;       // all members
    cf::GridMapping crs;                                          // the scene's CRS (of the maps); empty: local metres
};

SweepStats compute_stats(const SweepResult& sweep, const Scene& scene, const StatsDef& def = default_stats_def());

// The statistics file (formats/stats_file.hpp; written atomically, sweep_stats_file.cpp)
// and a folder of CSV tables (sweep_stats_csv.cpp); see docs/sweep.md for the contents.
void write_stats_file(const std::string& path, const SweepStats& s, const StatsDef& def, const std::string& sweep_file,
                      const std::string& scene_file, const std::string& history);
void write_stats_csv(const std::string& dir, const SweepStats& s, const SweepResult& sweep);

}  // namespace flotsam::sweep
