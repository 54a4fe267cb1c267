// The frames of a stage-one flow file (formats/flow_file.hpp) as the debris replay reads
// them: FrameSource opens and checks the file, knows its grid, frame times, bed and
// tiles (the file's chunks), and reads any cells of a frame as depth and discharge,
// decoding the stored tiles itself where the file's layout allows
// (formats/tile_decoder.hpp), else through netCDF. FrameReadAhead reads one frame on a
// background thread meanwhile.
//
// The netCDF and HDF5 libraries are not thread-safe: one read at a time per file, on
// whichever thread (the read-ahead's caller waits for it before reading itself).
#pragma once
#include <cstddef>
#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/background_task.hpp"
#include "common/cf.hpp"
#include "common/grid.hpp"
#include "common/netcdf.hpp"
#include "debris/flow_sampler.hpp"
#include "formats/tile_decoder.hpp"

namespace flotsam::debris {

inline constexpr std::size_t no_frame = std::size_t(-1);

// What is read of a frame: a window and which of its tiles (all: the whole window).
struct FrameArea {
    CellWindow window;
    std::vector<char> tiles;  // per tile over the window, row-major; empty: all of them
    bool operator==(const FrameArea&) const = default;
};

// One stored frame on a window: depth, x- and y-discharge, row-major x fastest.
struct Frame {
    std::size_t index = no_frame;
    std::vector<float> h, qx, qy;                 // [m], [m²/s], [m²/s]
    std::vector<float> slab;                      // one tile run as read, before it is placed
    std::vector<TileDecoder::StoredTile> stored;  // the tiles as stored (decode_tiles)
    // With a ground (FrameWindow::set_ground): depth at its cell centres over the ground
    // cells of area.window [m].
    std::vector<float> ground_depth;
    FrameArea area;  // what of the frame is read
};

// The tiles (tile_x × tile_y cells, aligned to the grid's origin) that a window touches.
struct TileRange {
    int ti0 = 0, tj0 = 0, nti = 0, ntj = 0;
};

// CPU time of the calling thread [s].
double thread_cpu_seconds();

// What a stored flow is, read once when it is opened: what the checks against a scene,
// the estimate of a run and the files written from it need.
struct FlowDescription {
    std::string path;
    std::vector<double> frame_times;     // [s], increasing
    std::vector<float> bed;              // z on the whole grid [m]
    double dry_depth = 0.0;              // [m] the file's dry_depth_m, else flow_names::fallback_dry_depth
    double largest_speed = 0.0;          // of its max_speed map [m/s] (0 when it has none): what a run's steps are estimated from
    std::string scene_sha256;            // SHA-256 of the scene it was computed on ("" in flows written before it)
    std::string scene_buildings_sha256;  // that scene's building mask (formats/scene.hpp; "" in flows written before it)
    cf::GridMapping crs;                 // the CF grid mapping of its fields; empty: local metres
    double start_time() const { return frame_times.front(); }  // [s]
    double end_time() const { return frame_times.back(); }     // [s]
};

class FrameSource {
public:
    // Opens `path` and checks it is a flow file: h, u, v found by standard_name with
    // dims (time, y, x), z(y, x), x, y, time increasing. Errors name the file and the
    // missing piece. With `decode_tiles`, h, u, v's chunks are decoded here where the
    // file's layout allows, by `decode_threads` threads (the reading one among them).
    FrameSource(const std::string& path, bool decode_tiles, int decode_threads);

    const FlowDescription& description() const { return desc_; }
    const std::string& path() const { return desc_.path; }
    const Grid& grid() const { return grid_; }
    // Moves the frame of positions: grid() is then relative to (x_origin, y_origin) [m].
    void set_origin(double x_origin, double y_origin) {
        grid_.x0 -= x_origin;
        grid_.y0 -= y_origin;
    }
    // The first frame time after t (the last frame's when none) [s].
    double next_frame_time(double t) const;

    TileRange tiles_of(const CellWindow& w) const;
    // The cells of tile (ti, tj) within w.
    CellWindow tile_cells(const CellWindow& w, int ti, int tj) const;
    bool tile_loaded(const FrameArea& a, int ti, int tj) const;  // tile (ti, tj) of the grid is read on a
    int tile_x() const { return tile_x_; }                       // the file's chunk edge in x [cells] (64 where not chunked)
    int tile_y() const { return tile_y_; }                       // the same in y [cells]
    // The cells of area a that are read: its window, or each row of its tiles as runs.
    std::vector<CellWindow> read_rects(const FrameArea& a) const;

    // Reads frame `frame` on area `a` into f (cells outside a's tiles: zero); returns the
    // CPU time it took [s]. Touches only f and the file.
    double read_frame(Frame& f, std::size_t frame, const FrameArea& a) const;
    // Reads cells `rects` of frame `frame` into f's arrays laid out on window w. Returns
    // the CPU time of the threads that helped the calling one [s].
    double read_cells(Frame& f, std::size_t frame, const CellWindow& w, const std::vector<CellWindow>& rects) const;

private:
    // Reads cells r of frame `frame` through netCDF into f's arrays laid out on window w,
    // and checks them; with `decoded`, the values are there (decode_tiles) and are only
    // checked.
    void read_rect(Frame& f, std::size_t frame, const CellWindow& w, const CellWindow& r, bool decoded) const;
    // Reads cells `rects` of frame `frame` through decoder_, its tiles decoded on
    // decode_threads_ threads (tiles never written: through netCDF). Returns the CPU time
    // of the threads that helped the calling one [s].
    double decode_tiles(Frame& f, std::size_t frame, const CellWindow& w, const std::vector<CellWindow>& rects) const;

    nc::File file_;
    int decode_threads_ = 1;
    FlowDescription desc_;
    Grid grid_;
    int var_h_ = -1, var_u_ = -1, var_v_ = -1;
    float scale_h_ = 1.0f, scale_u_ = 1.0f, scale_v_ = 1.0f;  // the file's units to m and m/s (1: as flotsam writes)
    int tile_x_ = 64, tile_y_ = 64;
    std::unique_ptr<TileDecoder> decoder_;  // h, u, v's chunks; null: read through netCDF
};

// One frame read on a background thread while the caller goes on (common/background_task.hpp).
// Between start() and finish() only the thread touches frame() and the file.
class FrameReadAhead {
public:
    // Reads a frame on an area into a Frame; returns the CPU time it took [s].
    using Reader = std::function<double(Frame&, std::size_t, const FrameArea&)>;
    ~FrameReadAhead() { wait(); }  // its job writes into *this and reads the file

    // Starts reading frame `frame` on area `a` with `read`. A read under way is finished
    // (or dropped) first.
    void start(std::size_t frame, FrameArea a, Reader read);
    // The frame started and not yet finished; no_frame: none.
    std::size_t wanted() const { return wanted_; }
    const FrameArea& area() const { return area_; }  // the area it is read on
    // Waits for a read under way; it stays for finish().
    void wait();
    // Waits for the read started and forgets it; frame() then holds what it read.
    struct Finished {
        std::exception_ptr error;  // what the read threw (null: nothing)
        double cpu_seconds = 0.0;  // CPU time of the read [s]
    };
    Finished finish();
    Frame& frame() { return frame_; }

private:
    Frame frame_;
    FrameArea area_;
    double cpu_seconds_ = 0.0;
    std::size_t wanted_ = no_frame;
    BackgroundTask task_;  // last: destroyed (its job waited for) first
};

}  // namespace flotsam::debris
