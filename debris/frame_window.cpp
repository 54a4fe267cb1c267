// The frames held around t over the loaded window (debris/frame_window.hpp).
#include "debris/frame_window.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <utility>

#include "common/error.hpp"

namespace flotsam::debris {

FrameWindow::FrameWindow(FrameSource source, bool cubic) : source_(std::move(source)), cubic_(cubic) {
    window_ = CellWindow{0, grid().nx, 0, grid().ny};
}

void FrameWindow::set_origin(double x_origin, double y_origin) {
    source_.set_origin(x_origin, y_origin);
    ground_grid_.x0 -= x_origin;
    ground_grid_.y0 -= y_origin;
}

double FrameWindow::read_frame(Frame& f, std::size_t frame, const FrameArea& a) const {
    const double start_cpu = thread_cpu_seconds();
    const double reading_cpu = source_.read_frame(f, frame, a);
    if (has_ground()) depth_over_ground(f, a);
    return reading_cpu + thread_cpu_seconds() - start_cpu;
}

double FrameWindow::refit_frame(Frame& f, const FrameArea& to) {
    const double start_cpu = thread_cpu_seconds();
    double helpers_cpu = 0.0;
    if (!(f.area == to)) {
        const CellWindow &w = to.window, old = f.area.window;
        const std::size_t n = std::size_t(w.i1 - w.i0) * std::size_t(w.j1 - w.j0);
        const std::size_t wnx = std::size_t(w.i1 - w.i0), onx = std::size_t(old.i1 - old.i0);
        std::vector<float>* fields[3] = {&f.h, &f.qx, &f.qy};
        std::vector<float>* olds[3] = {&refit_spare_.h, &refit_spare_.qx, &refit_spare_.qy};
        for (int k = 0; k < 3; ++k) {
            std::swap(*fields[k], *olds[k]);
            fields[k]->assign(n, 0.0f);  // as read_frame: cells not read are dry and never sampled
        }
        // A tile the old window held whole within the new one is copied; the rest are read.
        const TileRange t = source_.tiles_of(w);
        FrameArea fresh{w, std::vector<char>(std::size_t(t.nti * t.ntj), 0)};
        for (int tj = t.tj0; tj < t.tj0 + t.ntj; ++tj)
            for (int ti = t.ti0; ti < t.ti0 + t.nti; ++ti) {
                if (!source_.tile_loaded(to, ti, tj)) continue;
                const CellWindow c = source_.tile_cells(w, ti, tj);
                if (!source_.tile_loaded(f.area, ti, tj) || !old.contains(c)) {
                    fresh.tiles[std::size_t((tj - t.tj0) * t.nti + (ti - t.ti0))] = 1;
                    continue;
                }
                for (int k = 0; k < 3; ++k)
                    for (int j = c.j0; j < c.j1; ++j)
                        std::copy_n(olds[k]->data() + std::size_t(j - old.j0) * onx + std::size_t(c.i0 - old.i0), c.i1 - c.i0,
                                    fields[k]->data() + std::size_t(j - w.j0) * wnx + std::size_t(c.i0 - w.i0));
            }
        const std::vector<CellWindow> rects = source_.read_rects(fresh);
        try {
            helpers_cpu = source_.read_cells(f, f.index, w, rects);
        } catch (...) {
            f.index = no_frame;  // half refit: held by no role, read anew if needed again
            throw;
        }
        for (const CellWindow& r : rects) stats_.cells_read += std::size_t(r.i1 - r.i0) * std::size_t(r.j1 - r.j0);
        f.area = to;
        ++stats_.frames_refit;
    }
    if (has_ground()) depth_over_ground(f, to);  // on the new window, or over a new ground
    return thread_cpu_seconds() - start_cpu + helpers_cpu;
}

void FrameWindow::load(Frame& f, std::size_t frame) {
    const auto start_clock = std::chrono::steady_clock::now();
    if (!take_read_ahead(f, frame)) {
        wait_read_ahead();  // one netCDF caller at a time; a frame read ahead stays for a later role
        stats_.load_cpu_seconds += read_frame(f, frame, area());
        count_read(area());
    }
    stats_.load_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_clock).count();
}

FrameWindow::~FrameWindow() {
    if (ahead_) ahead_->wait();  // its job writes into *ahead_ and reads the file
}

// Never moved with a read under way: World::advance_to finishes each read it starts.
FrameWindow::FrameWindow(FrameWindow&&) noexcept = default;

void FrameWindow::read_ahead(double t) {
    if (!loaded_) return;
    std::size_t need[4];
    frames_needed(t, need);
    std::size_t next = no_frame;
    for (int r = 0; r < 4 && next == no_frame; ++r) {
        bool held = false;
        for (int q = 0; q < 4; ++q) held = held || role(q).index == need[r];
        if (!held) next = need[r];
    }
    if (next == no_frame) return;
    if (!ahead_) ahead_ = std::make_unique<FrameReadAhead>();
    if (ahead_->wanted() == next) return;  // under way already; on an earlier window, refit when taken
    drop_read_ahead();
    ahead_->start(next, area(), [this](Frame& f, std::size_t frame, const FrameArea& a) { return read_frame(f, frame, a); });
}

void FrameWindow::wait_read_ahead() {
    if (ahead_) ahead_->wait();
}

void FrameWindow::finish_read_ahead() {
    const auto start_clock = std::chrono::steady_clock::now();
    wait_read_ahead();  // the frame (or its error) stays for prepare()
    stats_.load_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_clock).count();
}

bool FrameWindow::take_read_ahead(Frame& f, std::size_t frame) {
    if (!ahead_ || ahead_->wanted() != frame) return false;
    const FrameReadAhead::Finished done = ahead_->finish();
    count_read(ahead_->area());
    stats_.load_cpu_seconds += done.cpu_seconds;
    if (done.error) {
        // A frame that fails its checks is reported where it is needed, as without
        // read-ahead; one never needed is never reported. Read on a window since moved,
        // the bad cells may lie outside the new one: read it there instead.
        if (ahead_->area() == area()) std::rethrow_exception(done.error);
        return false;
    }
    std::swap(f, ahead_->frame());  // f's arrays are the next read's
    ++stats_.frames_read_ahead;
    if (!(f.area == area())) stats_.load_cpu_seconds += refit_frame(f, area());  // the window moved since the read began
    return true;
}

void FrameWindow::drop_read_ahead() {
    if (!ahead_ || ahead_->wanted() == no_frame) return;
    const FrameReadAhead::Finished done = ahead_->finish();  // an error here is of a frame not needed
    count_read(ahead_->area());
    stats_.load_cpu_seconds += done.cpu_seconds;
}

void FrameWindow::count_read(const FrameArea& a) {
    ++stats_.frames_loaded;
    const auto cells = [](const CellWindow& c) { return std::size_t(c.i1 - c.i0) * std::size_t(c.j1 - c.j0); };
    stats_.window_cells += cells(a.window);
    for (const CellWindow& r : source_.read_rects(a)) stats_.cells_read += cells(r);
}

void FrameWindow::hold(const std::size_t (&need)[4]) {
    const bool cubic = cubic_;
    const int r0 = cubic ? 0 : 1, r1 = cubic ? 4 : 3;
    Frame held[4];
    for (int r = 0; r < 4; ++r) held[r] = std::move(frames_[r]);
    // A held frame that no role needs lends its arrays to a frame read anew: reading then
    // neither allocates nor touches fresh pages.
    bool spare[4];
    for (int q = 0; q < 4; ++q) {
        spare[q] = true;
        for (int r = r0; r < r1; ++r) spare[q] = spare[q] && held[q].index != need[r];
    }
    for (int r = r0; r < r1; ++r) {
        Frame& f = frames_[r];
        f.index = no_frame;
        for (int q = r0; q < r && f.index == no_frame; ++q)  // the same frame in an earlier role (at the ends)
            if (frames_[q].index == need[r]) f = frames_[q];
        for (int q = 0; q < 4 && f.index == no_frame; ++q)  // held already: keep it
            if (held[q].index == need[r]) {
                f = std::move(held[q]);
                held[q].index = no_frame;
            }
        if (f.index != no_frame) continue;
        for (int q = 0; q < 4; ++q)
            if (spare[q] && held[q].h.capacity() > 0) {
                f = std::move(held[q]);
                f.index = no_frame;
                spare[q] = false;
                break;
            }
        load(f, need[r]);
    }
    for (int r = 0; r < 4; ++r) {
        role_slot_[r] = cubic ? r : std::clamp(r, 1, 2);
        h_.role[r] = role(r).h.data();
        qx_.role[r] = role(r).qx.data();
        qy_.role[r] = role(r).qy.data();
        ground_depth_.role[r] = role(r).ground_depth.data();
    }
    loaded_ = true;
}

void FrameWindow::frames_needed(double t, std::size_t (&need)[4]) const {
    const std::size_t n = source_.description().frame_times.size();
    std::size_t k = std::size_t(std::upper_bound(source_.description().frame_times.begin(), source_.description().frame_times.end(), t) -
                                source_.description().frame_times.begin());
    k = k == 0 ? 0 : k - 1;
    const std::size_t k1 = std::min(k + 1, n - 1);
    const bool cubic = cubic_;
    need[0] = cubic && k > 0 ? k - 1 : k;
    need[1] = k;
    need[2] = k1;
    need[3] = cubic ? std::min(k1 + 1, n - 1) : k1;
}

void FrameWindow::prepare(double t) {
    std::size_t need[4];
    frames_needed(t, need);
    if (loaded_) {
        bool same = true;
        for (int r = 0; r < 4; ++r) same = same && role(r).index == need[r];
        if (same) return;
    }
    hold(need);
}

void FrameWindow::set_window(const CellWindow& w) {
    CellWindow c{std::clamp(w.i0, 0, grid().nx - 2), std::clamp(w.i1, 2, grid().nx), std::clamp(w.j0, 0, grid().ny - 2),
                 std::clamp(w.j1, 2, grid().ny)};
    c.i1 = std::max(c.i1, c.i0 + 2);
    c.j1 = std::max(c.j1, c.j0 + 2);
    set_area(FrameArea{c, {}});
}

namespace {
CellWindow widened(const CellWindow& w, int by) { return CellWindow{w.i0 - by, w.i1 + by, w.j0 - by, w.j1 + by}; }
}  // namespace

void FrameWindow::set_regions(const std::vector<CellWindow>& regions) {
    if (regions.empty()) return;
    CellWindow box{grid().nx, 0, grid().ny, 0};
    std::vector<CellWindow> wide;
    for (const CellWindow& r : regions) {
        const CellWindow c = widened(r, region_margin);
        wide.push_back(CellWindow{std::clamp(c.i0, 0, grid().nx - 2), std::clamp(c.i1, 2, grid().nx),
                                  std::clamp(c.j0, 0, grid().ny - 2), std::clamp(c.j1, 2, grid().ny)});
        box = CellWindow{std::min(box.i0, wide.back().i0), std::max(box.i1, wide.back().i1), std::min(box.j0, wide.back().j0),
                         std::max(box.j1, wide.back().j1)};
    }
    // Whole tiles (cut only by the grid's edge): a tile is then the same cells in every
    // window that loads it, and a refit keeps it.
    box = CellWindow{box.i0 / source_.tile_x() * source_.tile_x(),
                     std::min(grid().nx, (box.i1 + source_.tile_x() - 1) / source_.tile_x() * source_.tile_x()),
                     box.j0 / source_.tile_y() * source_.tile_y(),
                     std::min(grid().ny, (box.j1 + source_.tile_y() - 1) / source_.tile_y() * source_.tile_y())};
    FrameArea a{box, {}};
    const TileRange t = source_.tiles_of(box);
    a.tiles.assign(std::size_t(t.nti * t.ntj), 0);
    for (const CellWindow& r : wide) {
        const TileRange u = source_.tiles_of(r);
        for (int tj = u.tj0; tj < u.tj0 + u.ntj; ++tj)
            for (int ti = u.ti0; ti < u.ti0 + u.nti; ++ti) a.tiles[std::size_t((tj - t.tj0) * t.nti + (ti - t.ti0))] = 1;
    }
    if (std::all_of(a.tiles.begin(), a.tiles.end(), [](char c) { return c != 0; })) a.tiles.clear();
    set_area(std::move(a));
}

bool FrameWindow::covers(const CellWindow& w) const {
    const CellWindow c = widened(w, region_margin);
    const CellWindow need{std::max(c.i0, 0), std::min(c.i1, grid().nx), std::max(c.j0, 0), std::min(c.j1, grid().ny)};
    if (!window_.contains(need)) return false;
    if (window_tiles_.empty()) return true;
    const TileRange t = source_.tiles_of(window_), u = source_.tiles_of(need);
    for (int tj = u.tj0; tj < u.tj0 + u.ntj; ++tj)
        for (int ti = u.ti0; ti < u.ti0 + u.nti; ++ti)
            if (!window_tiles_[std::size_t((tj - t.tj0) * t.nti + (ti - t.ti0))]) return false;
    return true;
}

FlowReadStats FrameWindow::read_stats() const {
    FlowReadStats s = stats_;
    const TileRange t = source_.tiles_of(window_);
    s.tiles_loaded = window_tiles_.empty() ? std::size_t(t.nti * t.ntj)
                                           : std::size_t(std::count(window_tiles_.begin(), window_tiles_.end(), char(1)));
    return s;
}

void FrameWindow::set_area(FrameArea a) {
    if (a.window == window_ && a.tiles == window_tiles_ && loaded_) return;
    window_ = a.window;
    window_tiles_ = std::move(a.tiles);
    if (has_ground()) ground_window_ = ground_window(window_);
    reload();
}

void FrameWindow::reload() {
    if (!loaded_) return;
    const auto start_clock = std::chrono::steady_clock::now();
    wait_read_ahead();  // one netCDF caller at a time; the frame read ahead is refit when taken
    for (Frame& f : frames_)
        if (f.index != no_frame) stats_.load_cpu_seconds += refit_frame(f, area());
    stats_.load_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_clock).count();
    const std::size_t need[4] = {role(0).index, role(1).index, role(2).index, role(3).index};
    hold(need);  // the roles' arrays moved
}

void FrameWindow::set_ground(const Grid& grid, std::vector<float> z) {
    if (z.size() != grid.size()) fail(source_.path(), "ground", "elevation does not match its grid");
    drop_read_ahead();  // read without this ground
    ground_grid_ = grid;
    ground_z_ = std::move(z);
    ground_window_ = ground_window(window_);
    reload();
}

CellWindow FrameWindow::ground_window(const CellWindow& w) const {
    // A point sampled in w lies between the nodes x(w.i0) and x(w.i1 − 1) (cells_for), and
    // its bilinear stencil on the ground takes the centres either side of it: one more
    // centre each way covers round-off.
    const Grid& g = ground_grid_;
    const auto below = [](double f) { return int(std::floor(f)) - 1; };
    const int i0 = below((grid().x(w.i0) - g.x0) / g.dx), i1 = below((grid().x(w.i1 - 1) - g.x0) / g.dx) + 4;
    const int j0 = below((grid().y(w.j0) - g.y0) / g.dy), j1 = below((grid().y(w.j1 - 1) - g.y0) / g.dy) + 4;
    CellWindow c{std::clamp(i0, 0, g.nx - 2), std::clamp(i1, 2, g.nx), std::clamp(j0, 0, g.ny - 2), std::clamp(j1, 2, g.ny)};
    c.i1 = std::max(c.i1, c.i0 + 2);
    c.j1 = std::max(c.j1, c.j0 + 2);
    return c;
}

void FrameWindow::depth_over_ground(Frame& f, const FrameArea& a) const {
    const CellWindow& w = a.window;
    const CellWindow gw = ground_window(w);
    f.ground_depth.resize(std::size_t(gw.i1 - gw.i0) * std::size_t(gw.j1 - gw.j0));
    if (!a.tiles.empty()) std::fill(f.ground_depth.begin(), f.ground_depth.end(), 0.0f);  // under tiles not read: never sampled
    for (const CellWindow& r : source_.read_rects(a)) depth_over_ground(f, w, r);
}

void FrameWindow::depth_over_ground(Frame& f, const CellWindow& w, const CellWindow& r) const {
    const Grid& g = ground_grid_;
    const CellWindow gw = ground_window(w), gr = ground_window(r);
    const int wnx = w.i1 - w.i0, wny = w.j1 - w.j0, gnx = gw.i1 - gw.i0, rnx = gr.i1 - gr.i0;
    // A ground column's flow stencil (column i of the window, weight wx of column i + 1)
    // is the same in every row: worked out once per column.
    std::vector<int> column(static_cast<std::size_t>(rnx));
    std::vector<double> wx_of(static_cast<std::size_t>(rnx));
    for (int k = 0; k < rnx; ++k) {
        const double fx = (g.x(gr.i0 + k) - grid().x0) / grid().dx;
        column[std::size_t(k)] = std::clamp(int(std::floor(fx)) - w.i0, 0, wnx - 2);
        wx_of[std::size_t(k)] = std::clamp(fx - double(column[std::size_t(k)] + w.i0), 0.0, 1.0);
    }
    // Per flow node of the two rows in use: the level h + z and whether it is wet.
    std::vector<double> level_of(2 * std::size_t(wnx));
    std::vector<char> wet_of(2 * std::size_t(wnx));
    int rows_held = -1;  // the window row j whose pair (j, j + 1) the arrays hold
    for (int gj = gr.j0; gj < gr.j1; ++gj) {
        const double fy = (g.y(gj) - grid().y0) / grid().dy;
        const int j = std::clamp(int(std::floor(fy)) - w.j0, 0, wny - 2);
        const double wy = std::clamp(fy - double(j + w.j0), 0.0, 1.0);
        if (j != rows_held) {
            for (int row = 0; row < 2; ++row)
                for (int i = 0; i < wnx; ++i) {
                    const std::size_t n = std::size_t(j + row) * std::size_t(wnx) + std::size_t(i);
                    const double h = f.h[n];
                    wet_of[std::size_t(row * wnx + i)] = h > source_.description().dry_depth;
                    level_of[std::size_t(row * wnx + i)] = h + double(source_.description().bed[grid().index(w.i0 + i, w.j0 + j + row)]);
                }
            rows_held = j;
        }
        float* out = f.ground_depth.data() + std::size_t(gj - gw.j0) * std::size_t(gnx) + std::size_t(gr.i0 - gw.i0);
        const float* ground_z = ground_z_.data() + g.index(gr.i0, gj);
        for (int k = 0; k < rnx; ++k) {
            const int i = column[std::size_t(k)];
            const double wx = wx_of[std::size_t(k)];
            const double wc[4] = {(1.0 - wx) * (1.0 - wy), wx * (1.0 - wy), (1.0 - wx) * wy, wx * wy};
            const std::size_t node[4] = {std::size_t(i), std::size_t(i + 1), std::size_t(wnx + i), std::size_t(wnx + i + 1)};
            // The level bilinear over the wet nodes, their weights renormalised. A dry
            // node adds a zero to both sums (never -0: they start at +0), which leaves
            // them as they are: the same bits as skipping it, without the branch.
            double wet = 0.0, level = 0.0;
            for (int c = 0; c < 4; ++c) {
                const double weight = wet_of[node[c]] ? wc[c] : 0.0;
                wet += weight;
                level += weight * level_of[node[c]];
            }
            out[k] = wet > 0.0 ? float(std::max(0.0, level / wet - double(ground_z[k]))) : 0.0f;
        }
    }
}

}  // namespace flotsam::debris
