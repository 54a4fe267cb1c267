// The flow file: what stage one stores and stage two replays. One CF-1.11 NetCDF-4 file
// per run.
//
//   time(time)            double, "seconds since 2000-01-01 00:00:00" (a fixed epoch: a
//                         flume run has no date; tools still parse the units)
//   x(x), y(y)            double [m], cell centres of the output window
//   z(y, x)               float [m] bed elevation above still water, positive up
//   h(time, y, x)         float [m]     standard_name sea_floor_depth_below_sea_surface
//   u(time, y, x)         float [m s-1] standard_name sea_water_x_velocity
//   v(time, y, x)         float [m s-1] standard_name sea_water_y_velocity
//                         dry cells: h = 0, u = v = 0 (never NaN)
//   max_depth(y, x), max_speed(y, x)        over the whole run, sampled every step
//   arrival_time(y, x)    [s] first time h > arrival_depth (attribute); fill where never
//   gauge_* (gauge_time, gauge)             level, depth and velocity at named points
//   crs                   the scene's CF grid mapping, when it has one; every (y, x) and
//                         (time, y, x) field then names it (grid_mapping = "crs")
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

struct FlowFileDef {
    Grid window;                      // the grid of the stored fields
    std::vector<float> z;             // bed elevation on `window` [m]
    std::vector<double> frame_times;  // output times [s], all of them, fixed up front
    std::vector<FlowGauge> gauges;
    std::size_t gauge_samples = 0;                  // length of the gauge time axis
    double gauge_interval = 0.05;                   // [s]
    double arrival_depth = 0.025;                   // threshold of arrival_time [m]
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
    void sync() { file_.sync(); }
    void close() { file_.close(); }

private:
    explicit FlowWriter(nc::File f);
    void find_vars();
    nc::File file_;
    int h_ = -1, u_ = -1, v_ = -1, time_ = -1;
    int gt_ = -1, geta_ = -1, gh_ = -1, gu_ = -1, gv_ = -1;
    int maxd_ = -1, maxs_ = -1, arr_ = -1;
    std::size_t nx_ = 0, ny_ = 0, ngauge_ = 0;
};

// Names the flow variables go by, shared by writer and readers.
namespace flow_names {
inline constexpr const char* depth = "sea_floor_depth_below_sea_surface";
inline constexpr const char* x_velocity = "sea_water_x_velocity";
inline constexpr const char* y_velocity = "sea_water_y_velocity";
}  // namespace flow_names

}  // namespace flotsam
