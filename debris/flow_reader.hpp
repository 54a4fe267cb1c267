// Replays a stage-one flow file (formats/flow_file.hpp) at any point and time.
//
// Only the frames around the current time are held, over a sub-window of the grid
// (OpenDrift/Parcels style): the pair that brackets t for the linear interpolant in time,
// the four frames k−1 … k+2 for the cubic one (debris/time_kernels.hpp). Stored as float
// (as in the file); samples are double. Depth h and discharge (hu, hv) are interpolated
// in time and bilinearly in space with the same weights; velocity is then q / h. With the
// linear interpolant u is a depth-weighted mean of the corner velocities, so a wetting
// front (one wet corner, three dry) gives that corner's speed, never more. The cubic one
// is used node by node only where its depth passes the guard of time_kernels.hpp (never
// below the shallower frame around t, all four frames wet); elsewhere the node is linear,
// so fronts keep that property and the depth is never negative. Below the flow's dry
// tolerance (dry_depth(): the file's dry_depth_m, formats/flow_file.hpp) the velocity is
// zero, as in the run that wrote it.
//
// Read-ahead (optional, World's read_ahead): read_ahead(t) starts reading, on one
// background thread, the frame that prepare(t) will need and does not hold; prepare()
// then takes it instead of reading it. The frame read is the same (same file, frame and
// window, same code), so results are the same to the bit with it or without. The netCDF
// library is not thread-safe: while a read is under way, the caller makes no other
// netCDF call (finish_read_ahead() first; World::advance_to does so before returning).
//
// Before the first frame and past the last one the flow is held (steady, ∂/∂t = 0).
// Outside the grid the edge values are held. Sampling is const and thread-safe; loading
// (prepare, set_window) is not and belongs between parallel sweeps.
#pragma once
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "common/cf.hpp"
#include "common/enum_names.hpp"
#include "common/grid.hpp"
#include "common/netcdf.hpp"
#include "debris/kernels.hpp"
#include "debris/time_kernels.hpp"
#include "formats/tile_decoder.hpp"

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

// Depth and velocity at a point.
struct FlowPoint {
    double depth = 0.0;  // h [m]
    double u = 0.0;      // [m/s]
    double v = 0.0;      // [m/s]
};

// Plus the material acceleration Du/Dt = ∂u/∂t + (u·∇)u of the same interpolant.
struct FlowPointAccel : FlowPoint {
    double du_dt = 0.0;  // [m/s²]
    double dv_dt = 0.0;  // [m/s²]
};

// Index ranges [i0, i1) × [j0, j1) of grid cells.
struct CellWindow {
    int i0 = 0, i1 = 0, j0 = 0, j1 = 0;
    bool contains(const CellWindow& w) const { return w.i0 >= i0 && w.i1 <= i1 && w.j0 >= j0 && w.j1 <= j1; }
    bool operator==(const CellWindow&) const = default;
};

class FlowReader {
public:
    // Opens `path` and checks it is a flow file: h, u, v found by standard_name with
    // dims (time, y, x), z(y, x), x, y, time increasing. Errors name the file and the
    // missing piece.
    explicit FlowReader(const std::string& path, const FlowReaderDef& def = default_flow_reader_def());
    ~FlowReader();                      // waits for a read under way
    FlowReader(FlowReader&&) noexcept;  // not with a read under way
    FlowReader& operator=(FlowReader&&) = delete;

    const Grid& grid() const { return grid_; }
    // Moves the frame of positions: the x, y given to the sampling calls (and grid()) are
    // then relative to (x_origin, y_origin) [m]. For map coordinates (see World).
    void set_origin(double x_origin, double y_origin) {
        grid_.x0 -= x_origin;
        grid_.y0 -= y_origin;
        ground_grid_.x0 -= x_origin;
        ground_grid_.y0 -= y_origin;
    }
    // The ground the bodies stand on, finer than the flow's (docs/debris.md, "Ground finer
    // than the flow"): elevation z [m] on `grid` (positions in the frame of grid(), x
    // fastest), covering the flow's grid. Depth is then what a flow stored on that grid
    // would give with this flow's level: each frame, as it is loaded, is carried down to
    // the ground's cell centres as max(0, η − z_ground), η = h + z bilinear over the flow
    // stencil's wet nodes (h above the dry tolerance; their weights renormalised; no wet
    // node: dry); that depth is interpolated in time as the flow's is (the cubic under the
    // same guard) and bilinearly between the centres. Velocities and accelerations stay
    // the flow's own interpolants; min_depth() bounds the depth over the ground.
    void set_ground(const Grid& grid, std::vector<float> z);
    bool has_ground() const { return !ground_z_.empty(); }
    const std::vector<double>& frame_times() const { return times_; }
    double start_time() const { return times_.front(); }
    double end_time() const { return times_.back(); }
    const std::vector<float>& bed() const { return z_; }  // z on the whole grid [m]
    const std::string& path() const { return file_.path(); }
    // SHA-256 of the scene file the flow was computed on (attribute scene_sha256; empty
    // for flows written before it existed).
    std::string scene_sha256() const { return file_.att_text(NC_GLOBAL, "scene_sha256").value_or(""); }

    // The CF grid mapping of the flow's fields (empty: local metres).
    cf::GridMapping crs() const { return cf::read_crs(file_, file_.var_name(var_h_)); }
    // The largest speed of the flow's max_speed map [m/s] (0 when the file has none): what
    // a run's step count is estimated from before it starts.
    double largest_speed() const;
    // The building mask of the flow's scene, as the hydro run recorded it (attribute
    // scene_buildings_sha256,
    // formats/scene.hpp; empty for flows written before it existed).
    std::string scene_buildings_sha256() const { return file_.att_text(NC_GLOBAL, "scene_buildings_sha256").value_or(""); }

    const FlowReaderDef& def() const { return def_; }
    // The flow's dry tolerance [m]: the file's dry_depth_m, else flow_names::fallback_dry_depth.
    double dry_depth() const { return dry_depth_; }

    // The first frame time after t (end_time() when none).
    double next_frame_time(double t) const;
    // Loads (or keeps) the frames the interpolant needs on [t, next_frame_time(t)]: the
    // bracketing pair, and for the cubic one frame either side. Moving on by one frame
    // reads one new frame; each frame is read once while time advances.
    void prepare(double t);
    // Starts reading, in the background, the first frame that prepare(t) needs and does
    // not hold (none: nothing to do). A read under way for another frame is dropped; one
    // for the same frame on an earlier window is kept (it is refit when taken).
    void read_ahead(double t);
    // Waits for a read under way; the frame stays for prepare(). After it the caller may
    // use netCDF again.
    void finish_read_ahead();
    // Restricts loading to cells `w` (clamped to the grid). The frames held, and one read
    // ahead when it is taken, are brought to the new window: of each, only the tiles the
    // old window did not hold are read.
    void set_window(const CellWindow& w);
    // Loads, of the frames, only the tiles (the file's chunks) under the regions, each
    // widened by region_margin cells: far-apart bodies do not pay for the cells between
    // them. The window is then the regions' bounding box, widened to whole tiles (so that
    // a tile stays whole when the window moves); cells of it outside those tiles hold
    // zeros and must not be sampled (covers()). Refits the frames as set_window does.
    void set_regions(const std::vector<CellWindow>& regions);
    // Whether cells `w`, widened by region_margin, are loaded: sampling at points whose
    // stencils lie in w, the ground's depths included, reads loaded cells only.
    bool covers(const CellWindow& w) const;
    // Flow cells beyond a region that its samples read: the ground centres around a point
    // (ground_window) lie up to three flow cells past its stencil's nodes.
    static constexpr int region_margin = 3;
    const CellWindow& window() const { return window_; }
    std::size_t tiles_loaded() const;  // tiles of the window that are read [-]
    // The cells a box [x0, x1] × [y0, y1] needs for sampling (bilinear stencils included).
    CellWindow cells_for(double x0, double x1, double y0, double y1) const;
    std::size_t frames_loaded() const { return frames_loaded_; }          // frames read, read ahead ones included
    std::size_t frames_read_ahead() const { return frames_read_ahead_; }  // of them, read ahead and used
    std::size_t cells_read() const { return cells_read_; }                // cells of those frames read (tiles under the regions), refits' included
    std::size_t frames_refit() const { return frames_refit_; }            // frames brought to a moved window, only its new tiles read
    std::size_t window_cells() const { return window_cells_; }            // cells of their windows (what a dense read takes)
    double load_seconds() const { return load_seconds_; }          // wall time the caller spent reading or waiting for frames [s]
    double load_cpu_seconds() const { return load_cpu_seconds_; }  // CPU time of the reading, on whichever thread [s]

    // Samples at time t in the prepared interval (clamped into it). The point must lie
    // in the window (cells_for of it contained in window()); outside, values are clamped.
    FlowPoint sample(double x, double y, double t) const { return sample(x, y, at_time(t)); }
    FlowPointAccel sample_accel(double x, double y, double t) const;
    double depth(double x, double y, double t) const { return depth(x, y, at_time(t)); }

    // What sampling at time t needs of the time axis (the frames' weights), worked out
    // once for many points at the same t; valid until the next prepare() or set_window().
    struct TimeStencil {
        double a = 0.0;             // linear: weight of frame k+1 [-]
        double inv_dt = 0.0;        // 1 / frame interval, 0 where the flow is held [1/s]
        bool cubic = false;         // the cubic interpolant is on (its guard is per node)
        TimeWeights cubic_weights;  // set where it is
    };
    TimeStencil at_time(double t) const;
    // The same as sample(x, y, t) and depth(x, y, t) for ts = at_time(t), to the bit.
    FlowPoint sample(double x, double y, const TimeStencil& ts) const;
    double depth(double x, double y, const TimeStencil& ts) const;
    // The same for the n points p[k], into out[k], to the bit; faster than one by one (the
    // points' stencils and divisions overlap).
    void sample(const Vec2* p, int n, const TimeStencil& ts, FlowPoint* out) const;
    void depth(const Vec2* p, int n, const TimeStencil& ts, double* out) const;
    // Smallest stored depth over cells `w` in the two frames around t: a lower bound of
    // the interpolated depth anywhere inside those cells' stencils (for the cubic too,
    // by its guard).
    double min_depth(const CellWindow& w) const;

private:
    static constexpr std::size_t no_frame = std::size_t(-1);
    // What is loaded of a frame: a window and which of its tiles (all: the whole window).
    struct Area {
        CellWindow window;
        std::vector<char> tiles;  // per tile over the window, row-major; empty: all of them
        bool operator==(const Area&) const = default;
    };
    // One stored frame on the window: depth, x- and y-discharge, row-major x fastest.
    struct Frame {
        std::size_t index = no_frame;
        std::vector<float> h, qx, qy;
        std::vector<float> slab;          // one tile run as read, before it is placed
        std::vector<TileDecoder::StoredTile> stored;  // the tiles as stored (decode_frame)
        std::vector<float> ground_depth;  // with a ground: depth at its cell centres over ground_window(window) [m]
        Area area;                        // what of the frame is read
    };
    // The tiles (tile_x_ × tile_y_ cells, aligned to the grid's origin) that window w touches.
    struct TileRange {
        int ti0 = 0, tj0 = 0, nti = 0, ntj = 0;
    };
    // One field of the four roles (below), for the sampling loops.
    struct Field {
        const float* role[4] = {nullptr, nullptr, nullptr, nullptr};
    };
    struct Stencil;
    struct ReadAhead;  // the background thread and the frame it reads
    Stencil stencil(double x, double y, const TimeStencil& ts) const;
    // The bilinear stencil of (x, y) on grid g's cells `w` (arrays of w's size), with the
    // cubic guard on `depth`.
    void stencil_on(const Grid& g, const CellWindow& w, double x, double y, const TimeStencil& ts, const Field& depth,
                    Stencil& out) const;
    // The ground cells whose centres the points sampled in flow cells `w` need.
    CellWindow ground_window(const CellWindow& w) const;
    // Carries frame f (read on area a) down to the ground: f.ground_depth.
    void depth_over_ground(Frame& f, const Area& a) const;
    // The same for the ground cells of ground_window(r), r within a's window.
    void depth_over_ground(Frame& f, const CellWindow& w, const CellWindow& r) const;
    // Depth over the ground (set_ground) at (x, y).
    double ground_depth(double x, double y, const TimeStencil& ts) const;
    FlowPointAccel flow_accel(const Stencil& s) const;  // sample_accel on the flow's own depth
    // Smallest depth of `depth` (arrays on `window`) over cells w ∩ window in the two
    // frames around t.
    static double smallest_depth(const Field& depth, const CellWindow& window, const CellWindow& w);
    // The frames of roles 0..3 that the interpolant needs on [t, next_frame_time(t)].
    void frames_needed(double t, std::size_t (&need)[4]) const;
    // Puts frames need[r] into the roles r that the interpolant uses, reusing what is held.
    void hold(const std::size_t (&need)[4]);
    void reload();  // brings the held frames to the window and ground (after a change of either)
    // Brings frame f, read on f.area, to area `to`: the tiles both load are kept, only the
    // others read, and the frame carried down to the ground again. The same bits as
    // reading it on `to`. Returns the CPU time it took [s].
    double refit_frame(Frame& f, const Area& to);
    bool tile_loaded(const Area& a, int ti, int tj) const;  // tile (ti, tj) of the grid is read on a
    void load(Frame& f, std::size_t frame);
    TileRange tiles_of(const CellWindow& w) const;
    // The cells of tile (ti, tj) within w.
    CellWindow tile_cells(const CellWindow& w, int ti, int tj) const;
    void set_area(Area a);
    void count_read(const Area& a);  // a frame read on area a
    // Reads frame `frame` on area `a` into f; returns the CPU time it took [s]. Touches
    // only f and the file (the read-ahead thread runs it).
    double read_frame(Frame& f, std::size_t frame, const Area& a) const;
    // Reads cells r of frame `frame` into f's arrays laid out on window w.
    // With `decoded`, the values are there (decode_frame) and are only checked.
    void read_cells(Frame& f, std::size_t frame, const CellWindow& w, const CellWindow& r, bool decoded) const;
    // Reads cells `rects` of frame `frame` through decoder_, its tiles decoded on
    // def_.decode_threads threads (tiles never written: through netCDF). Returns the CPU
    // time of the threads that helped the calling one [s].
    double decode_frame(Frame& f, std::size_t frame, const CellWindow& w, const std::vector<CellWindow>& rects) const;
    // The cells of area a that are read: its window, or each row of its tiles as runs.
    std::vector<CellWindow> read_rects(const Area& a) const;
    // Moves the frame read ahead into f if it is frame `frame` on the current window.
    bool take_read_ahead(Frame& f, std::size_t frame);
    void wait_read_ahead();  // for a read under way, untimed
    void drop_read_ahead();  // waits for a read under way and forgets it
    const Frame& role(int r) const { return frames_[role_slot_[r]]; }

    nc::File file_;
    FlowReaderDef def_;
    double dry_depth_ = 0.0;
    Grid grid_;
    std::vector<double> times_;
    std::vector<float> z_;
    Grid ground_grid_{0, 0};       // set_ground's; nx = 0: the bodies stand on the flow's bed
    std::vector<float> ground_z_;  // [m] on ground_grid_
    int var_h_ = -1, var_u_ = -1, var_v_ = -1;
    float scale_h_ = 1.0f, scale_u_ = 1.0f, scale_v_ = 1.0f;  // the file's units to m and m/s (1: as flotsam writes)

    int tile_x_ = 64, tile_y_ = 64;   // the file's chunk edges in x and y [cells] (64 where not chunked)
    CellWindow window_;               // the cells loaded are within it
    std::vector<char> window_tiles_;  // Area::tiles of the loaded area
    Area area() const { return Area{window_, window_tiles_}; }
    bool loaded_ = false;
    std::size_t frames_loaded_ = 0;
    std::size_t frames_read_ahead_ = 0;
    std::size_t frames_refit_ = 0;
    std::size_t cells_read_ = 0, window_cells_ = 0;
    double load_seconds_ = 0.0;
    double load_cpu_seconds_ = 0.0;
    // Roles 0..3: frames k−1, k, k+1, k+2 around t (k, k+1 bracket t; a missing one is
    // its nearest neighbour). The linear interpolant holds roles 1 and 2 only and maps
    // 0 → 1, 3 → 2 (their weights are zero).
    Frame frames_[4];
    Frame refit_spare_;  // refit_frame's arrays for the old layout, kept for the next refit
    int role_slot_[4] = {0, 1, 2, 3};
    Field h_, qx_, qy_;                 // the roles' arrays, set when frames are loaded
    Field ground_depth_;                // the roles' depths over the ground (with one)
    CellWindow ground_window_;          // ground_window(window_)
    std::unique_ptr<ReadAhead> ahead_;  // made by the first read_ahead()
    std::unique_ptr<TileDecoder> decoder_;  // h, u, v's chunks; null: read through netCDF
};

}  // namespace flotsam::debris
