// The frames of a flow held around the current time, over a sub-window of the grid
// (OpenDrift/Parcels style): the pair that brackets t for the linear interpolant in time,
// the four frames k−1 … k+2 for the cubic one. Moving on by one frame reads one new
// frame; each frame is read once while time advances (debris/frame_source.hpp reads them).
//
// The window follows the bodies: set_regions() loads, of each frame, only the tiles (the
// file's chunks) under the regions, and a move refits the frames held, reading only the
// tiles they lacked. With a ground finer than the flow (set_ground), each frame, as it is
// read, is also carried down to the ground's cell centres.
//
// Read-ahead: read_ahead(t) starts reading, on one background thread, the frame that
// prepare(t) will need and does not hold; prepare() then takes it instead of reading it.
// The frame read is the same (same file, frame and window, same code), so results are
// the same to the bit with it or without. While a read is under way the caller makes no
// netCDF call on this file (finish_read_ahead() first).
//
// Loading (prepare, set_window, set_regions, set_ground) is not thread-safe; the arrays
// it leaves (h(), qx(), qy(), ground_depth()) are read by many threads between loads.
#pragma once
#include <cstddef>
#include <memory>
#include <vector>

#include "common/grid.hpp"
#include "debris/flow_sampler.hpp"
#include "debris/frame_source.hpp"

namespace flotsam::debris {

// One field in the four roles of the frames held, for the sampling loops: roles 0..3 are
// frames k−1, k, k+1, k+2 around t (k, k+1 bracket t; a missing one is its nearest
// neighbour). The linear interpolant holds roles 1 and 2 only and maps 0 → 1, 3 → 2
// (their weights are zero). Arrays on FrameWindow::window() (the ground's: on
// FrameWindow::ground_window()), row-major, x fastest.
struct FrameField {
    const float* role[4] = {nullptr, nullptr, nullptr, nullptr};
};

// What a FrameWindow (a FlowReader) has read.
struct FlowReadStats {
    std::size_t tiles_loaded = 0;       // tiles of the window that are read [-]
    std::size_t frames_loaded = 0;      // frames read, read ahead ones included
    std::size_t frames_read_ahead = 0;  // of them, read ahead and used
    std::size_t cells_read = 0;         // cells of those frames read (tiles under the regions), refits' included
    std::size_t frames_refit = 0;       // frames brought to a moved window, only its new tiles read
    std::size_t window_cells = 0;       // cells of their windows (what a dense read takes)
    double load_seconds = 0.0;          // wall time the caller spent reading or waiting for frames [s]
    double load_cpu_seconds = 0.0;      // CPU time of the reading, on whichever thread [s]
};

class FrameWindow {
public:
    // Frames of `source`; `cubic`: the four frames the cubic interpolant needs, else two.
    FrameWindow(FrameSource source, bool cubic);
    ~FrameWindow();                       // waits for a read under way
    FrameWindow(FrameWindow&&) noexcept;  // not with a read under way
    FrameWindow& operator=(FrameWindow&&) = delete;

    const FrameSource& source() const { return source_; }
    const Grid& grid() const { return source_.grid(); }
    // Moves the frame of positions (the flow's grid and the ground's) by (x_origin, y_origin) [m].
    void set_origin(double x_origin, double y_origin);

    // The ground the bodies stand on: elevation z [m] on `grid` (positions in the frame
    // of grid(), x fastest), covering the flow's grid. Each frame held, and each read
    // after, is carried down to the ground's cell centres as max(0, η − z_ground),
    // η = h + z bilinear over the flow stencil's wet nodes (h above the dry tolerance;
    // their weights renormalised; no wet node: dry).
    void set_ground(const Grid& grid, std::vector<float> z);
    bool has_ground() const { return !ground_z_.empty(); }
    const Grid& ground_grid() const { return ground_grid_; }
    // The ground cells whose centres the points sampled in flow cells `w` need.
    CellWindow ground_window(const CellWindow& w) const;
    const CellWindow& ground_window() const { return ground_window_; }  // ground_window(window())

    // Loads (or keeps) the frames the interpolant needs on [t, next frame time]: the
    // bracketing pair, and for the cubic one frame either side.
    void prepare(double t);
    bool loaded() const { return loaded_; }  // prepare() has loaded frames
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
    // Loads, of the frames, only the tiles under the regions, each widened by
    // region_margin cells. The window is then the regions' bounding box, widened to whole
    // tiles (so that a tile stays whole when the window moves); cells of it outside those
    // tiles hold zeros and must not be sampled (covers()). Refits the frames as
    // set_window does.
    void set_regions(const std::vector<CellWindow>& regions);
    // Whether cells `w`, widened by region_margin, are loaded.
    bool covers(const CellWindow& w) const;
    // Flow cells beyond a region that its samples read: the ground centres around a point
    // (ground_window) lie up to three flow cells past its stencil's nodes.
    static constexpr int region_margin = 3;
    const CellWindow& window() const { return window_; }

    // The frame in role r (0..3) and the fields of the roles.
    std::size_t frame_of_role(int r) const { return role(r).index; }
    const FrameField& h() const { return h_; }                        // depth [m]
    const FrameField& qx() const { return qx_; }                      // x-discharge hu [m²/s]
    const FrameField& qy() const { return qy_; }                      // y-discharge hv [m²/s]
    const FrameField& ground_depth() const { return ground_depth_; }  // depth over the ground [m]

    // What was read so far.
    FlowReadStats read_stats() const;

private:
    // Carries frame f (read on area a) down to the ground: f.ground_depth.
    void depth_over_ground(Frame& f, const FrameArea& a) const;
    // The same for the ground cells of ground_window(r), r within a's window.
    void depth_over_ground(Frame& f, const CellWindow& w, const CellWindow& r) const;
    // The frames of roles 0..3 that the interpolant needs on [t, next frame time].
    void frames_needed(double t, std::size_t (&need)[4]) const;
    // Puts frames need[r] into the roles r that the interpolant uses, reusing what is held.
    void hold(const std::size_t (&need)[4]);
    void reload();  // brings the held frames to the window and ground (after a change of either)
    // Brings frame f, read on f.area, to area `to`: the tiles both load are kept, only the
    // others read, and the frame carried down to the ground again. The same bits as
    // reading it on `to`. Returns the CPU time it took [s].
    double refit_frame(Frame& f, const FrameArea& to);
    void load(Frame& f, std::size_t frame);
    void set_area(FrameArea a);
    void count_read(const FrameArea& a);  // a frame read on area a
    // Reads frame `frame` on area `a` into f and carries it down to the ground; returns
    // the CPU time it took [s]. Touches only f and the file (the read-ahead thread runs it).
    double read_frame(Frame& f, std::size_t frame, const FrameArea& a) const;
    // Moves the frame read ahead into f if it is frame `frame` on the current window.
    bool take_read_ahead(Frame& f, std::size_t frame);
    void wait_read_ahead();  // for a read under way, untimed
    void drop_read_ahead();  // waits for a read under way and forgets it
    const Frame& role(int r) const { return frames_[role_slot_[r]]; }
    FrameArea area() const { return FrameArea{window_, window_tiles_}; }

    FrameSource source_;
    bool cubic_ = false;
    Grid ground_grid_{0, 0};       // set_ground's; nx = 0: the bodies stand on the flow's bed
    std::vector<float> ground_z_;  // [m] on ground_grid_

    CellWindow window_;               // the cells loaded are within it
    std::vector<char> window_tiles_;  // FrameArea::tiles of the loaded area
    bool loaded_ = false;
    FlowReadStats stats_;  // all but tiles_loaded (read_stats counts them)
    Frame frames_[4];    // the frames held; role r is frames_[role_slot_[r]]
    Frame refit_spare_;  // refit_frame's arrays for the old layout, kept for the next refit
    int role_slot_[4] = {0, 1, 2, 3};
    FrameField h_, qx_, qy_;                 // the roles' arrays, set when frames are loaded
    FrameField ground_depth_;                // the roles' depths over the ground (with one)
    CellWindow ground_window_;               // ground_window(window_)
    std::unique_ptr<FrameReadAhead> ahead_;  // made by the first read_ahead(); last: destroyed first
};

}  // namespace flotsam::debris
