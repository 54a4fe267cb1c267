// Water level and velocity along a model's boundary, in time: what drives a side from
// another run (hydro/forced_side.hpp), and the file `flotsam hydro --boundary-output`
// writes so that one run can drive a finer one. One CF-1.11 NetCDF-4 file,
// featureType "timeSeries":
//
//   time(time)              double, seconds since the flow file's epoch (cf::time_units)
//   x(station), y(station)  double [m], where each series stands (projection_x_coordinate
//                           and projection_y_coordinate with grid_mapping "crs" when the
//                           run has a CRS)
//   station_name(station)   text, "west_000" ...: the box side and the index along it
//   eta(time, station)      double [m] sea_surface_height_above_mean_sea_level (the still
//                           water level is 0); the bed's level where dry
//   u, v(time, station)     double [m s-1] sea_water_x_velocity, sea_water_y_velocity
//                           (along the grid's x and y); 0 where dry
//   depth(time, station)    double [m] sea_floor_depth_below_sea_surface
//   :flotsam_file_kind = "boundary"
//
// Any file with the same standard names is read the same way (data/boundary_forcing.hpp),
// gridded (time, y, x) or as series (time, station), in any CRS.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "common/cf.hpp"
#include "common/netcdf.hpp"

namespace flotsam {

namespace boundary_names {
inline constexpr const char* level = "sea_surface_height_above_mean_sea_level";
inline constexpr const char* x_velocity = "sea_water_x_velocity";
inline constexpr const char* y_velocity = "sea_water_y_velocity";
inline constexpr const char* depth = "sea_floor_depth_below_sea_surface";
inline constexpr const char* file_kind = "boundary";
}  // namespace boundary_names

// One side's forcing once placed in a scene: the level (and, where the source has it,
// the velocity) at points along the side, at the source's times.
struct SideRecord {
    std::string source;         // the file, for messages
    std::vector<double> time;   // [s] strictly increasing
    std::vector<double> along;  // [m] position of each point along the side (y on the west and
                                // east sides, x on the south and north), strictly increasing
    std::vector<double> level;  // [m] above still water, (time, point) row-major
    std::vector<double> u, v;   // [m s-1] along the scene's x and y, (time, point); empty: level only
    std::vector<double> depth;  // [m] water depth, (time, point), where the source has it; empty: none.
                                // Where it is 0 the source is dry there, whatever its level says
    bool has_velocity() const { return !u.empty(); }
    bool has_depth() const { return !depth.empty(); }
    std::size_t points() const { return along.size(); }
};

struct BoundaryFileDef {
    std::vector<double> x, y;                       // [m] station positions
    std::vector<std::string> names;                 // one per station
    std::map<std::string, std::string> attributes;  // global attributes (history, ...)
    cf::GridMapping crs;                            // the run's CRS; empty: local metres
};

class BoundaryWriter {
public:
    // Creates `path` (the caller passes a temporary name) and defines everything.
    BoundaryWriter(const std::string& path, const BoundaryFileDef& def);
    // Samples [first, first + count): times and (sample, station) arrays.
    void write(std::size_t first, std::size_t count, const std::vector<double>& time, const std::vector<double>& eta,
               const std::vector<double>& depth, const std::vector<double>& u, const std::vector<double>& v);
    void close() { file_.close(); }

private:
    nc::File file_;
    std::size_t stations_ = 0;
    int time_ = -1, eta_ = -1, depth_ = -1, u_ = -1, v_ = -1;
};

}  // namespace flotsam
