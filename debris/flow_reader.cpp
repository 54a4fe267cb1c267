// The flow file's samples: the time stencil and the interpolation in time and space over
// the frames held (debris/flow_reader.hpp).
#include "debris/flow_reader.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.hpp"
#include "debris/kernels.hpp"

namespace flotsam::debris {

FlowReaderDef default_flow_reader_def() { return FlowReaderDef{}; }

FlowReader::FlowReader(const std::string& path, const FlowReaderDef& def)
    : def_(def),
      frames_(FrameSource(path, def.decode_tiles, def.decode_threads), def.time_interpolation == TimeInterpolation::cubic) {}

FlowReader::TimeStencil FlowReader::at_time(double t) const {
    // Every sample goes through here: without frames it would read unallocated memory.
    if (!frames_.loaded()) fail(description().path, "", "sampled at t = " + std::to_string(t) + " s before prepare() loaded any frame");
    TimeStencil ts;
    ts.t = t;
    const std::vector<double>& times = description().frame_times;
    const double t0 = times[frames_.frame_of_role(1)], t1 = times[frames_.frame_of_role(2)];
    if (t1 > t0) {
        ts.a = std::clamp((t - t0) / (t1 - t0), 0.0, 1.0);
        if (t >= t0 && t <= t1) ts.inv_dt = 1.0 / (t1 - t0);
        if (def_.time_interpolation == TimeInterpolation::cubic) {
            const double tp = times[frames_.frame_of_role(0)], tn = times[frames_.frame_of_role(3)];
            ts.cubic_weights = catmull_rom_time_weights(ts.a, ts.inv_dt, (t1 - t0) / (t1 - tp), (t1 - t0) / (tn - t0));
            ts.cubic = true;
        }
    }
    return ts;
}

struct FlowReader::Stencil {
    std::size_t n[4] = {0, 0, 0, 0};               // node offsets in the window arrays: 00, 10, 01, 11
    double wx = 0.0, wy = 0.0;                     // bilinear weights of the +1 nodes
    double a = 0.0;                                // linear: weight of frame k+1
    double inv_dt = 0.0;                           // 1 / frame interval, 0 where the flow is held
    bool cubic[4] = {false, false, false, false};  // node c uses the cubic (it passed the guard)
    const TimeWeights* cubic_weights = nullptr;    // set where the cubic interpolant is on
    bool inside_x = true, inside_y = true;         // false where the point was clamped to the grid
};

FlowReader::Stencil FlowReader::stencil(double x, double y, const TimeStencil& ts) const {
    Stencil s;
    stencil_on(grid(), frames_.window(), x, y, ts, frames_.h(), s);
    return s;
}

// Fills `s` in place, every field: the batched samplers keep arrays of stencils, and a
// stencil returned by value and copied into one was read back as a whole right after
// being written field by field, which stalled the load (a third of the depth sampling).
void FlowReader::stencil_on(const Grid& g, const CellWindow& w, double x, double y, const TimeStencil& ts, const FrameField& depth,
                            Stencil& s) const {
    const Double2 f = Double2{x - g.x0, y - g.y0} / Double2{g.dx, g.dy};  // one packed division
    const double fx = f[0], fy = f[1];
    const int wnx = w.i1 - w.i0, wny = w.j1 - w.j0;
    int i = int(std::floor(fx)) - w.i0, j = int(std::floor(fy)) - w.j0;
    s.inside_x = i >= 0 && i <= wnx - 2;
    s.inside_y = j >= 0 && j <= wny - 2;
    i = std::clamp(i, 0, wnx - 2);
    j = std::clamp(j, 0, wny - 2);
    s.wx = std::clamp(fx - double(i + w.i0), 0.0, 1.0);
    s.wy = std::clamp(fy - double(j + w.j0), 0.0, 1.0);
    s.n[0] = std::size_t(j) * std::size_t(wnx) + std::size_t(i);
    s.n[1] = s.n[0] + 1;
    s.n[2] = s.n[0] + std::size_t(wnx);
    s.n[3] = s.n[2] + 1;
    s.a = ts.a;
    s.inv_dt = ts.inv_dt;
    s.cubic_weights = ts.cubic ? &ts.cubic_weights : nullptr;
    for (int c = 0; c < 4; ++c) {
        s.cubic[c] = false;
        if (!ts.cubic) continue;
        const std::size_t n = s.n[c];
        const double h[4] = {depth.role[0][n], depth.role[1][n], depth.role[2][n], depth.role[3][n]};
        s.cubic[c] = cubic_depth_admissible(apply_time_weights(ts.cubic_weights.w, h[0], h[1], h[2], h[3]), h, description().dry_depth);
    }
}

namespace {
// Value, and its x, y, t derivatives, of one field interpolated in time and bilinearly
// in space.
struct Interp {
    double val, ddx, ddy, ddt;
};
template <class S>
inline double bilinear(const double (&v)[4], const S& s) {
    return (1.0 - s.wy) * ((1.0 - s.wx) * v[0] + s.wx * v[1]) + s.wy * ((1.0 - s.wx) * v[2] + s.wx * v[3]);
}
}  // namespace

// One field at node c of the stencil, in time: its value and its d/dt, from the cubic
// where the node passed the guard, else from the two frames around t.
template <class S, class F>
inline double value_in_time(const S& s, const F& f, int c) {
    const std::size_t n = s.n[c];
    if (s.cubic[c]) return apply_time_weights(s.cubic_weights->w, f.role[0][n], f.role[1][n], f.role[2][n], f.role[3][n]);
    return linear_in_time(s.a, f.role[1][n], f.role[2][n]);
}
template <class S, class F>
inline double rate_in_time(const S& s, const F& f, int c) {
    const std::size_t n = s.n[c];
    if (s.cubic[c]) return apply_time_weights(s.cubic_weights->dw, f.role[0][n], f.role[1][n], f.role[2][n], f.role[3][n]);
    return linear_rate(s.inv_dt, f.role[1][n], f.role[2][n]);
}

// One field at the stencil's point: in time at each node, then bilinear in space.
template <class S, class F>
inline double value_at(const S& s, const F& f) {
    const double v[4] = {value_in_time(s, f, 0), value_in_time(s, f, 1), value_in_time(s, f, 2), value_in_time(s, f, 3)};
    return bilinear(v, s);
}

namespace {
// Points sampled together: their stencils and divisions are independent, so the
// processor overlaps them instead of waiting on each in turn.
constexpr int points_in_flight = 8;
}  // namespace

double FlowReader::ground_depth(double x, double y, const TimeStencil& ts) const {
    // Bilinear over the ground's cell centres, as a flow stored on the ground's grid is
    // sampled.
    Stencil s;
    stencil_on(frames_.ground_grid(), frames_.ground_window(), x, y, ts, frames_.ground_depth(), s);
    return value_at(s, frames_.ground_depth());
}

namespace {
// Depths at the points p[0..n) (n ≤ points_per_block) bilinear on grid g's cells `w`
// and linear in time between frames k (`now`) and k + 1 (`next`), weight `a` of k + 1:
// stencil_on and value_at for the linear interpolant, the same operations point by
// point (so the same bits), written as loops over the points that the compiler
// vectorises.
constexpr int points_per_block = 64;
void linear_depths(const Grid& g, const CellWindow& w, const float* now, const float* next, double a, const Vec2* p, int n,
                   double* out) {
    const int wnx = w.i1 - w.i0, wny = w.j1 - w.j0;
    double wx[points_per_block], wy[points_per_block];
    int node[points_per_block];  // the 00 node's offset in the window arrays
    // std::clamp and int(std::floor(v)) spelled out in selects and a truncation (the same
    // values), which vectorise.
    const auto unit = [](double v) { return v < 0.0 ? 0.0 : (1.0 < v ? 1.0 : v); };
    const auto floor_int = [](double v) {
        const int t = int(v);  // toward zero
        return double(t) > v ? t - 1 : t;
    };
    double px[points_per_block], py[points_per_block];  // the points as arrays of x and y, for the vectoriser
    for (int k = 0; k < n; ++k) {
        px[k] = p[k].x;
        py[k] = p[k].y;
    }
    const double x0 = g.x0, y0 = g.y0, dx = g.dx, dy = g.dy;
    const int i0 = w.i0, j0 = w.j0;
    for (int k = 0; k < n; ++k) {
        const double fx = (px[k] - x0) / dx, fy = (py[k] - y0) / dy;
        const int i = std::min(std::max(floor_int(fx) - i0, 0), wnx - 2);
        const int j = std::min(std::max(floor_int(fy) - j0, 0), wny - 2);
        wx[k] = unit(fx - double(i + i0));
        wy[k] = unit(fy - double(j + j0));
        node[k] = j * wnx + i;
    }
    for (int k = 0; k < n; ++k) {
        const std::size_t n0 = std::size_t(node[k]), n2 = n0 + std::size_t(wnx);
        const double v[4] = {linear_in_time(a, now[n0], next[n0]), linear_in_time(a, now[n0 + 1], next[n0 + 1]),
                             linear_in_time(a, now[n2], next[n2]), linear_in_time(a, now[n2 + 1], next[n2 + 1])};
        out[k] = (1.0 - wy[k]) * ((1.0 - wx[k]) * v[0] + wx[k] * v[1]) + wy[k] * ((1.0 - wx[k]) * v[2] + wx[k] * v[3]);
    }
}
}  // namespace

void FlowReader::depth(const Vec2* p, int n, const TimeStencil& ts, double* out) const {
    // Over a ground its depths on its centres, else the flow's own, sampled alike.
    const bool g = has_ground();
    const Grid& cells = g ? frames_.ground_grid() : grid();
    const CellWindow& window = g ? frames_.ground_window() : frames_.window();
    const FrameField& depth = g ? frames_.ground_depth() : frames_.h();
    if (!ts.cubic) {
        for (int k0 = 0; k0 < n; k0 += points_per_block)
            linear_depths(cells, window, depth.role[1], depth.role[2], ts.a, p + k0, std::min(points_per_block, n - k0), out + k0);
        return;
    }
    for (int k0 = 0; k0 < n; k0 += points_in_flight) {
        const int m = std::min(points_in_flight, n - k0);
        Stencil s[points_in_flight];
        for (int k = 0; k < m; ++k) stencil_on(cells, window, p[k0 + k].x, p[k0 + k].y, ts, depth, s[k]);
        for (int k = 0; k < m; ++k) out[k0 + k] = value_at(s[k], depth);
    }
}

void FlowReader::sample(const Vec2* p, int n, const TimeStencil& ts, FlowPoint* out) const {
    for (int k0 = 0; k0 < n; k0 += points_in_flight) {
        const int m = std::min(points_in_flight, n - k0);
        Stencil s[points_in_flight];
        double h[points_in_flight], qx[points_in_flight], qy[points_in_flight];
        for (int k = 0; k < m; ++k) stencil_on(grid(), frames_.window(), p[k0 + k].x, p[k0 + k].y, ts, frames_.h(), s[k]);
        for (int k = 0; k < m; ++k) {
            h[k] = value_at(s[k], frames_.h());
            qx[k] = value_at(s[k], frames_.qx());
            qy[k] = value_at(s[k], frames_.qy());
            out[k0 + k] = FlowPoint{has_ground() ? ground_depth(p[k0 + k].x, p[k0 + k].y, ts) : h[k], 0.0, 0.0};
        }
        for (int k = 0; k < m; ++k) {
            FlowPoint& q = out[k0 + k];
            if (h[k] < description().dry_depth) continue;
            const Double2 uv = Double2{qx[k], qy[k]} / Double2{h[k], h[k]};
            q.u = uv[0];
            q.v = uv[1];
        }
    }
}

FlowPointAccel FlowReader::sample_accel(double x, double y, double t) const {
    const TimeStencil ts = at_time(t);
    FlowPointAccel p = flow_accel(stencil(x, y, ts));
    if (has_ground()) p.depth = ground_depth(x, y, ts);
    return p;
}

FlowPointAccel FlowReader::flow_accel(const Stencil& s) const {
    const double gx = s.inside_x ? 1.0 / grid().dx : 0.0, gy = s.inside_y ? 1.0 / grid().dy : 0.0;
    auto interp = [&](const FrameField& f) {
        const double v[4] = {value_in_time(s, f, 0), value_in_time(s, f, 1), value_in_time(s, f, 2), value_in_time(s, f, 3)};
        const double rate[4] = {rate_in_time(s, f, 0), rate_in_time(s, f, 1), rate_in_time(s, f, 2), rate_in_time(s, f, 3)};
        Interp r;
        r.val = bilinear(v, s);
        r.ddx = ((1.0 - s.wy) * (v[1] - v[0]) + s.wy * (v[3] - v[2])) * gx;
        r.ddy = ((1.0 - s.wx) * (v[2] - v[0]) + s.wx * (v[3] - v[1])) * gy;
        r.ddt = bilinear(rate, s);
        return r;
    };
    const Interp h = interp(frames_.h());
    FlowPointAccel p;
    p.depth = h.val;
    if (h.val < description().dry_depth) return p;
    const Interp qx = interp(frames_.qx()), qy = interp(frames_.qy());
    const Double2 uv = Double2{qx.val, qy.val} / Double2{h.val, h.val};
    p.u = uv[0];
    p.v = uv[1];
    if (h.val < def_.accel_depth) return p;
    // u = q / h, so ∂u = (∂q − u ∂h) / h for each of ∂t, ∂x, ∂y.
    const Double4 d4 = Double4{qx.ddt - p.u * h.ddt, qx.ddx - p.u * h.ddx, qx.ddy - p.u * h.ddy, qy.ddt - p.v * h.ddt} /
                       Double4{h.val, h.val, h.val, h.val};
    const Double2 d2 = Double2{qy.ddx - p.v * h.ddx, qy.ddy - p.v * h.ddy} / Double2{h.val, h.val};
    const double ut = d4[0], ux = d4[1], uy = d4[2], vt = d4[3], vx = d2[0], vy = d2[1];
    p.du_dt = ut + p.u * ux + p.v * uy;
    p.dv_dt = vt + p.u * vx + p.v * vy;
    return p;
}

double FlowReader::smallest_depth(const FrameField& depth, const CellWindow& window, const CellWindow& w) {
    const int i0 = std::max(w.i0, window.i0) - window.i0, i1 = std::min(w.i1, window.i1) - window.i0;
    const int j0 = std::max(w.j0, window.j0) - window.j0, j1 = std::min(w.j1, window.j1) - window.j0;
    const int wnx = window.i1 - window.i0;
    float m = 1e30f;
    for (int r = 1; r <= 2; ++r)
        for (int j = j0; j < j1; ++j) {
            const float* row = depth.role[r] + std::size_t(j) * std::size_t(wnx);
#pragma omp simd reduction(min : m)
            for (int i = i0; i < i1; ++i) m = std::min(m, row[i]);
        }
    return double(m);
}

// Over the ground (set_ground) the depth at a point is a bilinear mean of the ground
// centres' depths around it, interpolated in time between the frames around t (the cubic
// only where it stays above the shallower of those two): at least the smallest of those
// centres' depths in the two frames; likewise the flow's own.
double FlowReader::min_depth(const CellWindow& w) const {
    return has_ground() ? smallest_depth(frames_.ground_depth(), frames_.ground_window(), frames_.ground_window(w))
                        : smallest_depth(frames_.h(), frames_.window(), w);
}

}  // namespace flotsam::debris
