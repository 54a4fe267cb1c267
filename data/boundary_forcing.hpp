// Another model's water level (and velocity) on a boundary, read from a CF NetCDF file
// and placed along one side of a scene (formats/boundary_file.hpp, SideRecord), for
// `flotsam hydro --<side>-forcing FILE`.
//
// The file holds either gridded fields (time, y, x) or series at stations (time, station)
// with their coordinates, in any CRS: projected x/y with a grid mapping, or longitude and
// latitude. Variables are found by CF standard name: the level by
// sea_surface_height_above_mean_sea_level (or _above_geoid, sea_surface_height,
// sea_surface_elevation); the velocity, optional, by sea_water_x_velocity and
// sea_water_y_velocity (along the file's own axes) or eastward_ and
// northward_sea_water_velocity; the depth, optional, by sea_floor_depth_below_sea_surface
// (where it is 0 the source is dry, and its level is only its ground). Units are
// converted (common/units.hpp); time is the
// file's time coordinate in seconds from its own origin, which is the run's t = 0.
//
// Placement: stations are carried into the scene's CRS and those within reach of the side
// (a scene cell, or half the stations' spacing, from its edge line) give the points along
// it; gridded fields are read bilinearly at the side's edge-cell positions carried into the
// file's CRS. Velocities are turned from the file's axes (or east and north) to the
// scene's x and y where the two CRSs differ. Errors name the file and what is wrong: no
// CRS (or one the scene cannot be placed in), the side not covered, time not increasing,
// gaps, fill values or values that are not finite.
#pragma once
#include <cmath>
#include <string>

#include "common/cf.hpp"
#include "common/grid.hpp"
#include "formats/boundary_file.hpp"

namespace flotsam::data {

// What a run needs of a forcing file besides its side: the scene's elevations, which its
// levels must stay near, and the run's span, which its times must cover.
struct ForcingNeeds {
    double bed_min = std::nan("");          // [m] the scene's lowest bed; NaN: levels unchecked against it
    double t_start = 0.0;                   // [s] the run's start
    double t_end = std::nan("");            // [s] the run's end; NaN: times unchecked against it
    std::string option = "--west-forcing";  // where the file was given, for messages
};
// How far a level may lie from the scene's lowest bed [m]: the depth hydro's own state
// check stops at (no ocean is deeper).
inline constexpr double max_forcing_depth = 11000.0;

// `side`: "west", "east", "south" or "north" of `grid`, whose CRS is `crs` (empty: local
// metres). Besides the placement errors above, the values are checked for what the side
// needs (docs/reliability.md): depths not negative, levels within max_forcing_depth of
// `needs.bed_min`, speeds at most 1000 m/s; the times must cover [t_start, t_end] (to
// within one of the file's own steps at the end), and the record must fit in memory
// (its times x points, named with the file) before it is read.
SideRecord read_side_forcing(const std::string& path, const std::string& side, const Grid& grid,
                             const cf::GridMapping& crs, const ForcingNeeds& needs = {});

}  // namespace flotsam::data
