#include "debris/flow_reader.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "common/error.hpp"
#include "hydro/flow_file.hpp"

namespace flotsam::debris {

FlowReaderDef default_flow_reader_def() { return FlowReaderDef{}; }

namespace {

// A flow field found by standard_name, with dims (time, y, x).
int find_field(const nc::File& f, const char* standard_name, const char* short_name) {
    int nvars = 0;
    f.check(nc_inq_nvars(f.id(), &nvars), "number of variables");
    for (int v = 0; v < nvars; ++v) {
        const auto sn = f.att_text(v, "standard_name");
        if (!sn || *sn != standard_name) continue;
        if (f.dim_names(v) == std::vector<std::string>{"time", "y", "x"}) return v;
    }
    fail(f.path(), "", std::string("not a flow file: no variable (time, y, x) with standard_name '") + standard_name + "' (the " +
                           short_name + " of a stage-one flow)");
}

}  // namespace

FlowReader::FlowReader(const std::string& path, const FlowReaderDef& def) : file_(nc::File::open_read(path)), def_(def) {
    var_h_ = find_field(file_, flow_names::depth, "depth h");
    var_u_ = find_field(file_, flow_names::x_velocity, "x velocity u");
    var_v_ = find_field(file_, flow_names::y_velocity, "y velocity v");
    for (const char* name : {"time", "x", "y", "z"})
        if (!file_.has_var(name)) fail(path, "", std::string("not a flow file: no variable '") + name + "'");
    times_ = nc::read_finite(file_, "time");
    grid_ = grid_from_coordinates(nc::read_finite(file_, "x"), nc::read_finite(file_, "y"), path);
    if (grid_.nx < 2 || grid_.ny < 2) fail(path, "x, y", "a flow needs at least 2 x 2 cells");
    if (times_.empty()) fail(path, "variable 'time'", "no frames");
    for (std::size_t k = 1; k < times_.size(); ++k)
        if (!(times_[k] > times_[k - 1])) fail(path, "variable 'time'", "frame times must increase (frame " + std::to_string(k) + ")");
    const int vz = file_.var("z");
    if (file_.shape(vz) != std::vector<std::size_t>{std::size_t(grid_.ny), std::size_t(grid_.nx)})
        fail(path, "variable 'z'", "shape is not (y, x)");
    z_ = file_.get_float(vz);
    window_ = CellWindow{0, grid_.nx, 0, grid_.ny};
}

double FlowReader::next_frame_time(double t) const {
    const auto it = std::upper_bound(times_.begin(), times_.end(), t);
    return it == times_.end() ? times_.back() : *it;
}

void FlowReader::load(std::size_t slot, std::size_t frame) {
    const auto start_clock = std::chrono::steady_clock::now();
    const std::size_t ni = std::size_t(window_.i1 - window_.i0), nj = std::size_t(window_.j1 - window_.j0), n = ni * nj;
    const std::vector<std::size_t> start = {frame, std::size_t(window_.j0), std::size_t(window_.i0)}, count = {1, nj, ni};
    h_[slot].resize(n);
    qx_[slot].resize(n);
    qy_[slot].resize(n);
    file_.get_slab(var_h_, start, count, h_[slot].data());
    file_.get_slab(var_u_, start, count, qx_[slot].data());
    file_.get_slab(var_v_, start, count, qy_[slot].data());
    for (std::size_t k = 0; k < n; ++k) {
        const float h = h_[slot][k];
        if (!std::isfinite(h) || !std::isfinite(qx_[slot][k]) || !std::isfinite(qy_[slot][k]))
            fail(path(), "frame " + std::to_string(frame), "h, u or v is not finite (a flow file stores 0, never NaN)");
        qx_[slot][k] *= h;  // u → hu
        qy_[slot][k] *= h;
    }
    slot_frame_[slot] = frame;
    ++frames_loaded_;
    load_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_clock).count();
}

void FlowReader::prepare(double t) {
    const std::size_t n = times_.size();
    std::size_t k = std::size_t(std::upper_bound(times_.begin(), times_.end(), t) - times_.begin());
    k = k == 0 ? 0 : k - 1;
    const std::size_t k1 = std::min(k + 1, n - 1);
    if (loaded_ && slot_frame_[0] == k && slot_frame_[1] == k1) return;
    if (loaded_ && slot_frame_[1] == k) {  // moving forward one frame: keep the newer one
        std::swap(h_[0], h_[1]);
        std::swap(qx_[0], qx_[1]);
        std::swap(qy_[0], qy_[1]);
        slot_frame_[0] = k;
    } else {
        load(0, k);
    }
    if (k1 == k) {
        h_[1] = h_[0];
        qx_[1] = qx_[0];
        qy_[1] = qy_[0];
        slot_frame_[1] = k1;
    } else {
        load(1, k1);
    }
    pair_ = k;
    loaded_ = true;
}

void FlowReader::set_window(const CellWindow& w) {
    CellWindow c{std::clamp(w.i0, 0, grid_.nx - 2), std::clamp(w.i1, 2, grid_.nx), std::clamp(w.j0, 0, grid_.ny - 2), std::clamp(w.j1, 2, grid_.ny)};
    c.i1 = std::max(c.i1, c.i0 + 2);
    c.j1 = std::max(c.j1, c.j0 + 2);
    if (c.i0 == window_.i0 && c.i1 == window_.i1 && c.j0 == window_.j0 && c.j1 == window_.j1 && loaded_) return;
    window_ = c;
    if (!loaded_) return;
    const std::size_t f0 = slot_frame_[0], f1 = slot_frame_[1];
    load(0, f0);
    if (f1 == f0) {
        h_[1] = h_[0];
        qx_[1] = qx_[0];
        qy_[1] = qy_[0];
        slot_frame_[1] = f1;
    } else {
        load(1, f1);
    }
}

CellWindow FlowReader::cells_for(double x0, double x1, double y0, double y1) const {
    // The bilinear stencil of x uses nodes floor(fx) and floor(fx) + 1.
    const int i0 = int(std::floor((x0 - grid_.x0) / grid_.dx)), i1 = int(std::floor((x1 - grid_.x0) / grid_.dx)) + 2;
    const int j0 = int(std::floor((y0 - grid_.y0) / grid_.dy)), j1 = int(std::floor((y1 - grid_.y0) / grid_.dy)) + 2;
    return CellWindow{std::clamp(i0, 0, grid_.nx - 2), std::clamp(i1, 2, grid_.nx), std::clamp(j0, 0, grid_.ny - 2), std::clamp(j1, 2, grid_.ny)};
}

struct FlowReader::Stencil {
    std::size_t n00 = 0, n10 = 0, n01 = 0, n11 = 0;  // node offsets in the window arrays
    double wx = 0.0, wy = 0.0;                       // bilinear weights of the +1 nodes
    double a = 0.0;                                  // weight of the later frame
    double inv_dt = 0.0;                             // 1 / frame interval, 0 where the flow is held
    bool inside_x = true, inside_y = true;           // false where the point was clamped to the grid
};

FlowReader::Stencil FlowReader::stencil(double x, double y, double t) const {
    Stencil s;
    const double fx = (x - grid_.x0) / grid_.dx, fy = (y - grid_.y0) / grid_.dy;
    const int wnx = window_.i1 - window_.i0, wny = window_.j1 - window_.j0;
    int i = int(std::floor(fx)) - window_.i0, j = int(std::floor(fy)) - window_.j0;
    s.inside_x = i >= 0 && i <= wnx - 2;
    s.inside_y = j >= 0 && j <= wny - 2;
    i = std::clamp(i, 0, wnx - 2);
    j = std::clamp(j, 0, wny - 2);
    s.wx = std::clamp(fx - double(i + window_.i0), 0.0, 1.0);
    s.wy = std::clamp(fy - double(j + window_.j0), 0.0, 1.0);
    s.n00 = std::size_t(j) * std::size_t(wnx) + std::size_t(i);
    s.n10 = s.n00 + 1;
    s.n01 = s.n00 + std::size_t(wnx);
    s.n11 = s.n01 + 1;
    const double t0 = times_[slot_frame_[0]], t1 = times_[slot_frame_[1]];
    if (t1 > t0) {
        s.a = std::clamp((t - t0) / (t1 - t0), 0.0, 1.0);
        if (t >= t0 && t <= t1) s.inv_dt = 1.0 / (t1 - t0);
    }
    return s;
}

namespace {
// Value, and its x, y, t derivatives, of one field interpolated linearly in time and
// bilinearly in space.
struct Interp {
    double val, ddx, ddy, ddt;
};
template <class S>
inline double lerp_node(const std::vector<float>& f0, const std::vector<float>& f1, std::size_t n, const S& s) {
    return (1.0 - s.a) * double(f0[n]) + s.a * double(f1[n]);
}
template <class S>
inline double bilinear(double v00, double v10, double v01, double v11, const S& s) {
    return (1.0 - s.wy) * ((1.0 - s.wx) * v00 + s.wx * v10) + s.wy * ((1.0 - s.wx) * v01 + s.wx * v11);
}
}  // namespace

double FlowReader::depth(double x, double y, double t) const {
    const Stencil s = stencil(x, y, t);
    return bilinear(lerp_node(h_[0], h_[1], s.n00, s), lerp_node(h_[0], h_[1], s.n10, s), lerp_node(h_[0], h_[1], s.n01, s),
                    lerp_node(h_[0], h_[1], s.n11, s), s);
}

FlowPoint FlowReader::sample(double x, double y, double t) const {
    const Stencil s = stencil(x, y, t);
    auto at = [&](const std::vector<float>* f) {
        return bilinear(lerp_node(f[0], f[1], s.n00, s), lerp_node(f[0], f[1], s.n10, s), lerp_node(f[0], f[1], s.n01, s),
                        lerp_node(f[0], f[1], s.n11, s), s);
    };
    FlowPoint p;
    p.depth = at(h_);
    if (p.depth >= def_.dry_depth) {
        p.u = at(qx_) / p.depth;
        p.v = at(qy_) / p.depth;
    }
    return p;
}

FlowPointAccel FlowReader::sample_accel(double x, double y, double t) const {
    const Stencil s = stencil(x, y, t);
    const double gx = s.inside_x ? 1.0 / grid_.dx : 0.0, gy = s.inside_y ? 1.0 / grid_.dy : 0.0;
    auto interp = [&](const std::vector<float>* f) {
        const double v00 = lerp_node(f[0], f[1], s.n00, s), v10 = lerp_node(f[0], f[1], s.n10, s);
        const double v01 = lerp_node(f[0], f[1], s.n01, s), v11 = lerp_node(f[0], f[1], s.n11, s);
        Interp r;
        r.val = bilinear(v00, v10, v01, v11, s);
        r.ddx = ((1.0 - s.wy) * (v10 - v00) + s.wy * (v11 - v01)) * gx;
        r.ddy = ((1.0 - s.wx) * (v01 - v00) + s.wx * (v11 - v10)) * gy;
        auto dn = [&](std::size_t n) { return double(f[1][n]) - double(f[0][n]); };
        r.ddt = bilinear(dn(s.n00), dn(s.n10), dn(s.n01), dn(s.n11), s) * s.inv_dt;
        return r;
    };
    const Interp h = interp(h_);
    FlowPointAccel p;
    p.depth = h.val;
    if (h.val < def_.dry_depth) return p;
    const Interp qx = interp(qx_), qy = interp(qy_);
    p.u = qx.val / h.val;
    p.v = qy.val / h.val;
    if (h.val < def_.accel_depth) return p;
    // u = q / h, so ∂u = (∂q − u ∂h) / h for each of ∂t, ∂x, ∂y.
    const double ut = (qx.ddt - p.u * h.ddt) / h.val, ux = (qx.ddx - p.u * h.ddx) / h.val, uy = (qx.ddy - p.u * h.ddy) / h.val;
    const double vt = (qy.ddt - p.v * h.ddt) / h.val, vx = (qy.ddx - p.v * h.ddx) / h.val, vy = (qy.ddy - p.v * h.ddy) / h.val;
    p.du_dt = ut + p.u * ux + p.v * uy;
    p.dv_dt = vt + p.u * vx + p.v * vy;
    return p;
}

double FlowReader::min_depth(const CellWindow& w) const {
    const int i0 = std::max(w.i0, window_.i0) - window_.i0, i1 = std::min(w.i1, window_.i1) - window_.i0;
    const int j0 = std::max(w.j0, window_.j0) - window_.j0, j1 = std::min(w.j1, window_.j1) - window_.j0;
    const int wnx = window_.i1 - window_.i0;
    float m = 1e30f;
    for (int s = 0; s < 2; ++s)
        for (int j = j0; j < j1; ++j) {
            const float* row = h_[s].data() + std::size_t(j) * std::size_t(wnx);
            for (int i = i0; i < i1; ++i) m = std::min(m, row[i]);
        }
    return double(m);
}

}  // namespace flotsam::debris
