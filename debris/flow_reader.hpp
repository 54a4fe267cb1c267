// Replays a stage-one flow file (formats/flow_file.hpp) at any point and time: the
// FlowSampler (debris/flow_sampler.hpp) of a stored flow, built from a FrameSource (the
// file, debris/frame_source.hpp) and a FrameWindow (the frames held around t over the
// bodies' tiles, debris/frame_window.hpp).
//
// Frames are stored as float (as in the file); samples are double. Depth h and discharge
// (hu, hv) are interpolated in time (debris/time_kernels.hpp) and bilinearly in space
// with the same weights; velocity is then q / h. With the linear interpolant u is a
// depth-weighted mean of the corner velocities, so a wetting front (one wet corner, three
// dry) gives that corner's speed, never more. The cubic one is used node by node only
// where its depth passes the guard of time_kernels.hpp (never below the shallower frame
// around t, all four frames wet); elsewhere the node is linear, so fronts keep that
// property and the depth is never negative. Below the flow's dry tolerance (dry_depth():
// the file's dry_depth_m, formats/flow_file.hpp) the velocity is zero, as in the run
// that wrote it.
//
// Read-ahead (optional, World's read_ahead): see debris/frame_window.hpp; the results are
// the same to the bit with it or without. While a read is under way the caller makes no
// other netCDF call (finish_read_ahead() first; World::advance_to does so before
// returning).
//
// Before the first frame and past the last one the flow is held (steady, ∂/∂t = 0).
// Outside the grid the edge values are held. Sampling is const and thread-safe; loading
// (prepare, set_window, set_regions, set_ground) is not and belongs between parallel
// sweeps.
#pragma once
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "common/cf.hpp"
#include "common/enum_names.hpp"
#include "common/grid.hpp"
#include "debris/flow_sampler.hpp"
#include "debris/frame_source.hpp"
#include "debris/frame_window.hpp"
#include "debris/kernels.hpp"

namespace flotsam::debris {

// Interpolation between stored frames: linear in the two frames around t, or the cubic
// Catmull-Rom through the four frames around t (guarded, see above).
enum class TimeInterpolation { linear, cubic };
inline constexpr EnumNames<TimeInterpolation, 2> time_interpolation_names{
    "time interpolation", {{{TimeInterpolation::linear, "linear"}, {TimeInterpolation::cubic, "cubic"}}}};
constexpr const auto& enum_names(TimeInterpolation) { return time_interpolation_names; }

struct FlowReaderDef {
    // Below this depth Du/Dt is zero [m]. Not a dry tolerance (that one comes from the
    // file): a guard on the gradients of q/h, which blow up in thin water beside deep
    // water at a front; the inertia force there acts on a submerged volume of at most
    // L B × 1 mm (docs/debris.md, "Flow at the body").
    double accel_depth = 1e-3;
    TimeInterpolation time_interpolation = TimeInterpolation::linear;
    // Decode the stored chunks of h, u, v here (formats/tile_decoder.hpp: the values
    // netCDF gives, in about half its processor time) where the file's layout allows;
    // false: read them through netCDF.
    bool decode_tiles = true;
    // Threads that decode a frame's tiles, the reading thread among them. 0: one for a
    // reader on its own; debris::World takes as many as step its bodies (they wait for
    // that frame meanwhile).
    int decode_threads = 0;
};
FlowReaderDef default_flow_reader_def();

class FlowReader final : public FlowSampler {
public:
    // Opens `path` and checks it is a flow file: h, u, v found by standard_name with
    // dims (time, y, x), z(y, x), x, y, time increasing. Errors name the file and the
    // missing piece.
    explicit FlowReader(const std::string& path, const FlowReaderDef& def = default_flow_reader_def());

    const Grid& grid() const override { return frames_.grid(); }
    // Moves the frame of positions: the x, y given to the sampling calls (and grid()) are
    // then relative to (x_origin, y_origin) [m]. For map coordinates (see World).
    void set_origin(double x_origin, double y_origin) { frames_.set_origin(x_origin, y_origin); }
    // The ground the bodies stand on, finer than the flow's (docs/debris.md, "Ground finer
    // than the flow"): elevation z [m] on `grid` (positions in the frame of grid(), x
    // fastest), covering the flow's grid. Depth is then what a flow stored on that grid
    // would give with this flow's level: each frame, as it is loaded, is carried down to
    // the ground's cell centres (FrameWindow::set_ground); that depth is interpolated in
    // time as the flow's is (the cubic under the same guard) and bilinearly between the
    // centres. Velocities and accelerations stay the flow's own interpolants; min_depth()
    // bounds the depth over the ground.
    void set_ground(const Grid& grid, std::vector<float> z) { frames_.set_ground(grid, std::move(z)); }
    bool has_ground() const { return frames_.has_ground(); }

    const FrameSource& source() const { return frames_.source(); }
    // What the flow is: path, frame times, bed, dry depth, largest speed, its scene's
    // fingerprints, its CRS (read once when opened).
    const FlowDescription& description() const { return frames_.source().description(); }
    const FlowReaderDef& def() const { return def_; }

    // The first frame time after t (the last frame's when none) [s].
    double next_frame_time(double t) const { return source().next_frame_time(t); }
    // Loading, as FrameWindow's: the frames around t, over the window or regions.
    void prepare(double t) { frames_.prepare(t); }
    void read_ahead(double t) { frames_.read_ahead(t); }
    void finish_read_ahead() { frames_.finish_read_ahead(); }
    void set_window(const CellWindow& w) { frames_.set_window(w); }
    void set_regions(const std::vector<CellWindow>& regions) { frames_.set_regions(regions); }
    static constexpr int region_margin = FrameWindow::region_margin;
    // Whether cells `w`, widened by region_margin, are loaded: sampling at points whose
    // stencils lie in w, the ground's depths included, reads loaded cells only.
    bool covers(const CellWindow& w) const override { return frames_.covers(w); }
    const CellWindow& window() const { return frames_.window(); }
    // What was read (FrameWindow's counts).
    const FrameWindow& frames() const { return frames_; }
    FlowReadStats read_stats() const { return frames_.read_stats(); }

    // Samples at time t in the prepared interval (clamped into it). The point must lie
    // in the window (cells_for of it contained in window()); outside, values are clamped.
    using FlowSampler::depth;
    using FlowSampler::sample;
    // The frames' weights at t; valid until the next prepare() or set_window().
    TimeStencil at_time(double t) const override;
    void sample(const Vec2* p, int n, const TimeStencil& ts, FlowPoint* out) const override;
    void depth(const Vec2* p, int n, const TimeStencil& ts, double* out) const override;
    FlowPointAccel sample_accel(double x, double y, double t) const override;
    // Smallest stored depth over cells `w` in the two frames around t: a lower bound of
    // the interpolated depth anywhere inside those cells' stencils (for the cubic too,
    // by its guard).
    double min_depth(const CellWindow& w) const override;

private:
    struct Stencil;
    Stencil stencil(double x, double y, const TimeStencil& ts) const;
    // The bilinear stencil of (x, y) on grid g's cells `w` (arrays of w's size), with the
    // cubic guard on `depth`.
    void stencil_on(const Grid& g, const CellWindow& w, double x, double y, const TimeStencil& ts, const FrameField& depth,
                    Stencil& out) const;
    // Depth over the ground (set_ground) at (x, y).
    double ground_depth(double x, double y, const TimeStencil& ts) const;
    FlowPointAccel flow_accel(const Stencil& s) const;  // sample_accel on the flow's own depth
    // Smallest depth of `depth` (arrays on `window`) over cells w ∩ window in the two
    // frames around t.
    static double smallest_depth(const FrameField& depth, const CellWindow& window, const CellWindow& w);

    FlowReaderDef def_;
    FrameWindow frames_;
};

}  // namespace flotsam::debris
