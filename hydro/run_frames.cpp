// The output window, frame times, gauges and maxima of a hydro run (run_frames.hpp).
#include "hydro/run_frames.hpp"

#include <cmath>
#include <string>

#include "common/checks.hpp"
#include "common/error.hpp"

namespace flotsam::hydro {

Window make_window(const Grid& g, const std::optional<std::array<double, 4>>& w) {
    Window out;
    if (!w) {
        out.i1 = g.nx - 1;
        out.j1 = g.ny - 1;
    } else {
        const auto& b = *w;
        if (!(b[0] < b[1] && b[2] < b[3])) fail("", "--output-window", "needs x_min < x_max and y_min < y_max");
        // At least two cells each way inside the grid (a replayed flow interpolates).
        if (!(b[0] < g.x(g.nx - 2) && b[1] > g.x(1) && b[2] < g.y(g.ny - 2) && b[3] > g.y(1)))
            fail("", "--output-window",
                 "x " + number_text(b[0]) + " to " + number_text(b[1]) + ", y " + number_text(b[2]) + " to " + number_text(b[3]) +
                     " m does not cover two cells of the scene's grid (x " + number_text(g.x_min_edge()) + " to " +
                     number_text(g.x_max_edge()) + ", y " + number_text(g.y_min_edge()) + " to " + number_text(g.y_max_edge()) +
                     " m)");
        out.i0 = g.cell_i(b[0]);
        out.i1 = g.cell_i(b[1]);
        out.j0 = g.cell_j(b[2]);
        out.j1 = g.cell_j(b[3]);
    }
    out.grid = Grid{out.i1 - out.i0 + 1, out.j1 - out.j0 + 1, g.x(out.i0), g.y(out.j0), g.dx, g.dy};
    return out;
}

std::vector<double> frame_times(double duration, double interval) {
    check_range("--output-interval", interval, Range::positive("s"));
    check_allocation("--output-interval", number_text(interval) + " s over " + number_text(duration) + " s",
                     duration / interval + 2, sizeof(double), "frame times");
    std::vector<double> t;
    const long n = long(std::floor(duration / interval + 1e-9));
    for (long k = 0; k <= n; ++k) t.push_back(double(k) * interval);
    if (t.back() < duration - 1e-9) t.push_back(duration);
    if (t.size() < 2)
        fail("", "--duration",
             number_text(duration) + " s stores one frame (t = 0) only: a flow needs at least two; give a longer --duration");
    return t;
}

Gauges::Gauges(const std::vector<FlowGauge>& gauges, const Grid& g, double interval, double duration) : interval_(interval) {
    for (const auto& p : gauges) {
        if (!g.contains(p.x, p.y)) {
            std::string at = std::to_string(p.x);
            at += ", ";
            at += std::to_string(p.y);
            fail("", "gauge '" + p.name + "'", "position (" + at + ") is outside the grid");
        }
        points_.push_back(point_stencil(g, p.x, p.y));
    }
    check_range("--gauge-interval", interval, Range::positive("s"));
    if (!gauges.empty())
        check_allocation("--gauge-interval", number_text(interval) + " s over " + number_text(duration) + " s",
                         (duration / interval + 1) * double(gauges.size()), 4 * sizeof(float) + sizeof(double), "gauge samples");
    samples_ = gauges.empty() ? 0 : std::size_t(std::floor(duration / interval + 1e-9)) + 1;
}

void Gauges::record(double t0, const std::vector<GaugeSample>& a, double t1, const std::vector<GaugeSample>& b) {
    while (next_ < samples_) {
        const double ts = double(next_) * interval_;
        if (ts > t1 + 1e-12) break;
        if (ts >= t0 - 1e-12) {
            const double w = t1 > t0 ? std::clamp((ts - t0) / (t1 - t0), 0.0, 1.0) : 1.0;
            time_.push_back(ts);
            for (std::size_t g = 0; g < a.size(); ++g) {
                eta_.push_back(float((1 - w) * a[g].eta + w * b[g].eta));
                h_.push_back(float((1 - w) * a[g].h + w * b[g].h));
                u_.push_back(float((1 - w) * a[g].u + w * b[g].u));
                v_.push_back(float((1 - w) * a[g].v + w * b[g].v));
            }
        }
        ++next_;
    }
}
void Gauges::flush(FlowWriter& w) {
    w.write_gauges(flushed_, time_.size(), time_, eta_, h_, u_, v_);
    flushed_ += time_.size();
    time_.clear();
    eta_.clear();
    h_.clear();
    u_.clear();
    v_.clear();
}

// The maxima and arrival times of one row of cells, given their depth and velocities.
// Out of line and branch-free: it runs after every step, so it must vectorise.
void accumulate_row(std::size_t n, const double* h, const double* u, const double* v, double t, double arrival_depth,
                    float* __restrict max_depth, float* __restrict max_speed, float* __restrict arrival) {
    const float fill = float(kFill), arrival_time = float(t);
#pragma omp simd
    for (std::size_t i = 0; i < n; ++i) {
        // (Values, not references into the arrays, for std::max: else no vectorising.)
        const float depth = float(h[i]), speed = float(std::sqrt(u[i] * u[i] + v[i] * v[i]));
        const float depth_so_far = max_depth[i], speed_so_far = max_speed[i], arrived = arrival[i];
        max_depth[i] = std::max(depth_so_far, depth);
        max_speed[i] = std::max(speed_so_far, speed);
        arrival[i] = (h[i] > arrival_depth) & (arrived == fill) ? arrival_time : arrived;
    }
}

}  // namespace flotsam::hydro
