// What a hydro run stores besides the solver's state (run_driver.hpp): the output window and
// the frame times, the frames themselves, the gauges sampled between steps, and the
// maxima and arrival times accumulated after every step.
#pragma once
#include <algorithm>
#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "common/grid.hpp"
#include "formats/flow_file.hpp"
#include "hydro/column_range.hpp"
#include "hydro/point_samples.hpp"

namespace flotsam::hydro {

constexpr double kFill = 9.969209968386869e36;  // NetCDF's default float fill

// The cells of the scene's grid whose frames are stored.
struct Window {
    int i0 = 0, i1 = 0, j0 = 0, j1 = 0;  // inclusive interior cell ranges
    Grid grid;
};

// The window of `w` (x_min, x_max, y_min, y_max [m]), or the whole grid; throws naming
// --output-window when it is empty or covers less than two cells each way.
Window make_window(const Grid& g, const std::optional<std::array<double, 4>>& w);

// The stored frames' times [s]: 0, interval, ... and `duration` itself; throws naming the
// option when there are fewer than two, or too many to hold.
std::vector<double> frame_times(double duration, double interval);

using GaugeSample = PointSample;

// Accumulated over the run on the output window.
struct Summary {
    std::vector<float> max_depth, max_speed, arrival;
};

// Gauges at named points, read as hydro/point_samples.hpp says, every `interval`.
class Gauges {
public:
    // Checks the points and the sample count; throws naming the gauge or setting.
    Gauges(const std::vector<FlowGauge>& gauges, const Grid& g, double interval, double duration);
    std::size_t samples() const { return samples_; }
    std::size_t count() const { return points_.size(); }
    template <class S>
    std::vector<GaugeSample> read(const S& s) const {
        std::vector<GaugeSample> out;
        for (const PointStencil& p : points_) out.push_back(sample_point(s, p));
        return out;
    }
    // Records every sample time in (t0, t1] by linear interpolation between the states.
    void record(double t0, const std::vector<GaugeSample>& a, double t1, const std::vector<GaugeSample>& b);
    void flush(FlowWriter& w);  // writes the samples recorded since the last flush
    std::size_t next() const { return next_; }
    void resume_at(std::size_t next) { next_ = flushed_ = next; }

private:
    double interval_;
    std::vector<PointStencil> points_;
    std::size_t samples_ = 0, next_ = 0, flushed_ = 0;
    std::vector<double> time_;
    std::vector<float> eta_, h_, u_, v_;
};

// Calls f(q0, h, u, v) for each row of the window, rows in parallel: the depth and
// velocities of the row's cells (state_row) and the index of its first cell in window
// arrays.
template <class S, class F>
void for_each_window_row(const S& s, const Window& win, F&& f) {
    const std::size_t nx = std::size_t(win.grid.nx);
#pragma omp parallel
    {
        std::vector<double> h(nx), u(nx), v(nx);
#pragma omp for schedule(static)
        for (int j = win.j0; j <= win.j1; ++j) {
            s.state_row(j, win.i0, win.i1 + 1, h.data(), u.data(), v.data());
            f(win.grid.index(0, j - win.j0), h.data(), u.data(), v.data());
        }
    }
}

template <class S>
void write_frame(FlowWriter& w, std::size_t k, const S& s, const Window& win) {
    const std::size_t n = win.grid.size(), nx = std::size_t(win.grid.nx);
    std::vector<float> h(n), u(n), v(n);
    for_each_window_row(s, win, [&](std::size_t q0, const double* rh, const double* ru, const double* rv) {
        for (std::size_t i = 0; i < nx; ++i) {
            h[q0 + i] = float(rh[i]);
            u[q0 + i] = float(ru[i]);
            v[q0 + i] = float(rv[i]);
        }
    });
    w.write_frame(k, h, u, v);
}

// The maxima and arrival times of one row of cells, given their depth and velocities.
// Out of line and branch-free: it runs after every step, so it must vectorise.
[[gnu::noinline]] void accumulate_row(std::size_t n, const double* h, const double* u, const double* v, double t,
                                      double arrival_depth, float* __restrict max_depth, float* __restrict max_speed,
                                      float* __restrict arrival);

// Every step, so only where a row may hold water: a cell whose state is exactly zero
// raises no maximum and does not arrive (the maps start at 0 and the fill value).
template <class S>
void accumulate(Summary& sum, const S& s, const Window& win, double t, double arrival_depth) {
#pragma omp parallel
    {
        std::vector<double> h(std::size_t(win.grid.nx)), u(h.size()), v(h.size());
#pragma omp for schedule(static)
        for (int j = win.j0; j <= win.j1; ++j) {
            const ColumnRange c = s.wet_columns(j);
            const int i0 = std::max(win.i0, c.begin), i1 = std::min(win.i1 + 1, c.end);
            if (i0 >= i1) continue;
            s.state_row(j, i0, i1, h.data(), u.data(), v.data());
            const std::size_t q0 = win.grid.index(i0 - win.i0, j - win.j0);
            accumulate_row(std::size_t(i1 - i0), h.data(), u.data(), v.data(), t, arrival_depth, sum.max_depth.data() + q0,
                           sum.max_speed.data() + q0, sum.arrival.data() + q0);
        }
    }
}

}  // namespace flotsam::hydro
