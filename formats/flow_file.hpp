// The flow file: what stage one stores and stage two replays. One CF-1.11 NetCDF-4 file
// per run.
//
//   time(time)            double, "seconds since 2000-01-01 00:00:00" (a fixed epoch: a
//                         flume run has no date; tools still parse the units); its
//                         comment says the epoch stands for the start of the run
//   x(x), y(y)            double [m], cell centres of the output window
//   z(y, x)               float [m] bed elevation above still water, positive up
//   h(time, y, x)         float [m]     standard_name sea_floor_depth_below_sea_surface
//   u(time, y, x)         float [m s-1] standard_name sea_water_x_velocity
//   v(time, y, x)         float [m s-1] standard_name sea_water_y_velocity; long names
//                         "x-/y-component of ..." so QGIS pairs u, v as one vector
//                         dry cells: h = 0, u = v = 0 (never NaN)
//   max_depth(y, x), max_speed(y, x)        over the whole run, sampled every step
//   arrival_time(y, x)    [s] first time h > arrival_depth (attribute); fill where never
//   max_level(y, x)       [m] highest water level (z + max_depth); fill where never wet
//   flooded(y, x)         byte, 1 where h exceeded flood_depth (attribute) at some time
//   runup_elevation, runup_x, runup_y   scalars [m]: the highest ground that flooded and
//                         where (the first such cell, row by row from the south-west)
//   gauge_* (gauge_time, gauge)             level, depth and velocity at named points
//   :dry_depth_m          global attribute, the run's dry tolerance [m] (text or number)
//   crs                   the scene's CF grid mapping, when it has one; every (y, x) and
//                         (time, y, x) field then names it (grid_mapping = "crs"), so
//                         QGIS reads them all as one mesh
//
// h, u, v are chunked one frame deep in tiles (1, 64, 64) with shuffle + deflate, so a
// reader that wants a small window of one or two frames decompresses little.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "common/cf.hpp"
#include "common/grid.hpp"
#include "common/netcdf.hpp"

namespace flotsam {

struct FlowGauge {
    std::string name;
    double x = 0.0;  // [m]
    double y = 0.0;  // [m]
};

// Where the water went, from the run's largest depths on the output window.
struct RunupSummary {
    std::vector<float> max_level;      // [m] z + max_depth where wet at some time, else NaN (stored as fill)
    std::vector<std::int8_t> flooded;  // 1 where max_depth > flood_depth
    double elevation = 0.0;            // [m] highest z of a flooded cell; NaN when none flooded
    double x = 0.0, y = 0.0;           // [m] its cell centre
};
// From max_depth and z on `window` (row-major) with the threshold flood_depth [m].
RunupSummary runup_summary(const Grid& window, const std::vector<float>& z, const std::vector<float>& max_depth,
                           double flood_depth);

struct FlowFileDef {
    Grid window;                      // the grid of the stored fields
    std::vector<float> z;             // bed elevation on `window` [m]
    std::vector<double> frame_times;  // output times [s], all of them, fixed up front
    std::vector<FlowGauge> gauges;
    std::size_t gauge_samples = 0;                  // length of the gauge time axis
    double gauge_interval = 0.05;                   // [s]
    double arrival_depth = 0.025;                   // threshold of arrival_time [m]
    double flood_depth = 0.001;                     // threshold of `flooded` [m]
    int deflate_level = 1;                          // 0..9; 1 is nearly as small as 9 and much faster
    int chunk = 64;                                 // tile edge of the (1, chunk, chunk) chunks [cells]
    std::map<std::string, std::string> attributes;  // global attributes (title, history, ...)
    cf::GridMapping crs;                            // the scene's CRS; empty: local metres
};

class FlowWriter {
public:
    // Creates `path` (the caller passes a temporary name) and defines everything.
    FlowWriter(const std::string& path, const FlowFileDef& def);
    // Reopens a partial file written by an interrupted run, to continue after a restart.
    static FlowWriter reopen(const std::string& path);

    // Frame k of h, u, v on the window (row-major, x fastest).
    void write_frame(std::size_t k, const std::vector<float>& h, const std::vector<float>& u, const std::vector<float>& v);
    // Gauge samples [first, first + count) for all gauges; arrays are (sample, gauge).
    void write_gauges(std::size_t first, std::size_t count, const std::vector<double>& time, const std::vector<float>& eta,
                      const std::vector<float>& h, const std::vector<float>& u, const std::vector<float>& v);
    void write_summary(const std::vector<float>& max_depth, const std::vector<float>& max_speed,
                       const std::vector<float>& arrival_time);
    // The runup outputs (RunupSummary; formats/flow_file.hpp's header lists them).
    void write_runup(const RunupSummary& runup);
    void sync() { file_.sync(); }
    void close() { file_.close(); }

private:
    explicit FlowWriter(nc::File f);
    void find_vars();
    nc::File file_;
    int h_ = -1, u_ = -1, v_ = -1, time_ = -1;
    int gt_ = -1, geta_ = -1, gh_ = -1, gu_ = -1, gv_ = -1;
    int maxd_ = -1, maxs_ = -1, arr_ = -1;
    int max_level_ = -1, flooded_ = -1, runup_z_ = -1, runup_x_ = -1, runup_y_ = -1;
    std::size_t nx_ = 0, ny_ = 0, ngauge_ = 0;
};

// Names the flow variables go by, shared by writer and readers.
namespace flow_names {
inline constexpr const char* depth = "sea_floor_depth_below_sea_surface";
inline constexpr const char* x_velocity = "sea_water_x_velocity";
inline constexpr const char* y_velocity = "sea_water_y_velocity";
// Global attribute: the hydro run's dry tolerance [m] (below it a cell has no velocity),
// which the replay uses as its own. Files without it (written by another program, or
// by a FlowWriter whose caller set no attributes) get fallback_dry_depth, the value
// flotsam's hydro has always used by default.
inline constexpr const char* dry_depth_attribute = "dry_depth_m";
inline constexpr double fallback_dry_depth = 1e-5;  // [m]
}  // namespace flow_names

}  // namespace flotsam
