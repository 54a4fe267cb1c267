// Replays a stage-one flow file (hydro/flow_file.hpp) at any point and time.
//
// Only two frames are held: the pair that brackets the current time, over a sub-window
// of the grid (OpenDrift/Parcels style). Stored as float (as in the file); samples are
// double. Interpolation is linear in time and bilinear in space of depth h and discharge
// (hu, hv); velocity is then q / h. Because both are interpolated with the same weights,
// u is a depth-weighted mean of the corner velocities, so a wetting front (one wet
// corner, three dry) gives that corner's speed, never more. Below `dry_depth` the
// velocity is zero.
//
// Before the first frame and past the last one the flow is held (steady, ∂/∂t = 0).
// Outside the grid the edge values are held. Sampling is const and thread-safe; loading
// (prepare, set_window) is not and belongs between parallel sweeps.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "common/grid.hpp"
#include "common/netcdf.hpp"

namespace flotsam::debris {

struct FlowReaderDef {
    double dry_depth = 1e-5;    // below this interpolated depth the velocity is zero [m]
    double accel_depth = 1e-3;  // below this depth Du/Dt is zero (q/h gradients blow up at a front) [m]
};
FlowReaderDef default_flow_reader_def();

// Depth and velocity at a point.
struct FlowPoint {
    double depth = 0.0;   // h [m]
    double u = 0.0;       // [m/s]
    double v = 0.0;       // [m/s]
};

// Plus the material acceleration Du/Dt = ∂u/∂t + (u·∇)u of the same interpolant.
struct FlowPointAccel : FlowPoint {
    double du_dt = 0.0;   // [m/s²]
    double dv_dt = 0.0;   // [m/s²]
};

// Index ranges [i0, i1) × [j0, j1) of grid cells.
struct CellWindow {
    int i0 = 0, i1 = 0, j0 = 0, j1 = 0;
    bool contains(const CellWindow& w) const { return w.i0 >= i0 && w.i1 <= i1 && w.j0 >= j0 && w.j1 <= j1; }
};

class FlowReader {
public:
    // Opens `path` and checks it is a flow file: h, u, v found by standard_name with
    // dims (time, y, x), z(y, x), x, y, time increasing. Errors name the file and the
    // missing piece.
    explicit FlowReader(const std::string& path, const FlowReaderDef& def = default_flow_reader_def());

    const Grid& grid() const { return grid_; }
    const std::vector<double>& frame_times() const { return times_; }
    double start_time() const { return times_.front(); }
    double end_time() const { return times_.back(); }
    const std::vector<float>& bed() const { return z_; }   // z on the whole grid [m]
    const std::string& path() const { return file_.path(); }

    // The first frame time after t (end_time() when none).
    double next_frame_time(double t) const;
    // Loads (or keeps) the pair of frames bracketing [t, next_frame_time(t)].
    void prepare(double t);
    // Restricts loading to cells `w` (clamped to the grid); reloads the current pair.
    void set_window(const CellWindow& w);
    const CellWindow& window() const { return window_; }
    // The cells a box [x0, x1] × [y0, y1] needs for sampling (bilinear stencils included).
    CellWindow cells_for(double x0, double x1, double y0, double y1) const;
    std::size_t frames_loaded() const { return frames_loaded_; }
    double load_seconds() const { return load_seconds_; }  // wall time spent reading frames [s]

    // Samples at time t in the prepared interval (clamped into it). The point must lie
    // in the window (cells_for of it contained in window()); outside, values are clamped.
    FlowPoint sample(double x, double y, double t) const;
    FlowPointAccel sample_accel(double x, double y, double t) const;
    double depth(double x, double y, double t) const;
    // Smallest stored depth over cells `w` in both loaded frames: a lower bound of the
    // interpolated depth anywhere inside those cells' stencils.
    double min_depth(const CellWindow& w) const;

private:
    struct Stencil;
    Stencil stencil(double x, double y, double t) const;
    void load(std::size_t slot, std::size_t frame);

    nc::File file_;
    FlowReaderDef def_;
    Grid grid_;
    std::vector<double> times_;
    std::vector<float> z_;
    int var_h_ = -1, var_u_ = -1, var_v_ = -1;

    CellWindow window_;
    std::size_t pair_ = 0;          // frames pair_ and pair_ + 1 (or pair_ twice at the end)
    bool loaded_ = false;
    std::size_t frames_loaded_ = 0;
    double load_seconds_ = 0.0;
    // slot s: depth, x- and y-discharge on the window, row-major x fastest.
    std::vector<float> h_[2], qx_[2], qy_[2];
    std::size_t slot_frame_[2] = {std::size_t(-1), std::size_t(-1)};
};

}  // namespace flotsam::debris
