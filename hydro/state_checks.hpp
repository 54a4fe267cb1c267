// Finite or a named error: the checks a hydro run makes on its own state (issue 18).
//
// Before every stored frame and every checkpoint the whole state is scanned; the first
// cell whose depth or velocity is not finite, whose depth is negative or absurdly deep,
// or whose speed is absurd stops the run with the time, the cell, the variable and the
// volume, so a run never exits 0 with NaN in its fields and never writes them. A NaN
// does not shrink the CFL step (max() skips it), so the per-frame scan is what catches
// it; the step itself is checked every step.
#pragma once
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "common/grid.hpp"

namespace flotsam::hydro {

// Beyond these a state is absurd for any scene on Earth: deeper than the deepest ocean,
// faster than a wave in it (sqrt(g 11 km) = 330 m/s).
inline constexpr double absurd_depth = 1.1e4;              // [m]
inline constexpr double absurd_speed = 1.0e3;              // [m/s]
inline constexpr double negative_depth_tolerance = -1e-9;  // [m] round-off below zero
inline constexpr double absurd_step = 1e-9;                // [s] no shallow-water scene needs a shorter step

struct BadCell {
    int i = 0, j = 0;
    double x = 0.0, y = 0.0;  // cell centre [m]
    std::string variable;     // "depth h", "x velocity u", "y velocity v", "speed"
    double value = 0.0;
    std::string why;  // "not finite", "negative", "above 11000 m", ...
};

// The first bad cell in row-major order, from one row of depths and velocities.
std::optional<BadCell> check_row(const Grid& g, int j, int i0, const double* h, const double* u, const double* v, int n);

// Throws the named error for a bad cell found at time t [s].
[[noreturn]] void fail_bad_state(const std::string& out_file, double t, const BadCell& c, double volume_start, double volume_now);

// A stall: the stable step far below what the run has taken so far. A step below
// `collapse_ratio` of the median of all steps so far, for more than `collapse_steps`
// steps in a row, stops the run; the median is kept as a histogram of log10(dt) in
// hundredths of a decade (exact enough to place a factor of 1000, and the same whatever
// the run length).
inline constexpr double collapse_ratio = 1e-3;
inline constexpr int collapse_steps = 20;

class StepWatch {
public:
    // Records the stable step dt [s]; true when the run has stalled.
    bool stalled(double dt);
    double median() const;  // [s] of the steps recorded so far
    int steps_below() const { return below_; }

private:
    static constexpr int kBins = 2400;  // 1e-15 .. 1e9 s
    std::vector<long> bins_ = std::vector<long>(kBins, 0);
    long count_ = 0;
    int below_ = 0;
};

// The cell that sets the step: the largest (|u| + c)/dx + (|v| + c)/dy of a state.
struct FastestCell {
    int i = 0, j = 0;
    double x = 0.0, y = 0.0, depth = 0.0, speed = 0.0, bed = 0.0, rate = 0.0;
};
template <class S>
FastestCell fastest_cell(const S& s, const Grid& g, double gravity) {
    FastestCell f;
    std::vector<double> h(std::size_t(g.nx)), u(std::size_t(g.nx)), v(std::size_t(g.nx));
    for (int j = 0; j < g.ny; ++j) {
        s.state_row(j, 0, g.nx, h.data(), u.data(), v.data());
        for (int i = 0; i < g.nx; ++i) {
            const double c = std::sqrt(gravity * std::max(h[std::size_t(i)], 0.0));
            const double rate = (std::abs(u[std::size_t(i)]) + c) / g.dx + (std::abs(v[std::size_t(i)]) + c) / g.dy;
            if (rate > f.rate)
                f = {i, j, g.x(i), g.y(j), h[std::size_t(i)], std::hypot(u[std::size_t(i)], v[std::size_t(i)]),
                     s.level(i, j) - h[std::size_t(i)], rate};
        }
    }
    return f;
}

// Throws the named error of a stalled run at time t with step dt.
[[noreturn]] void fail_stalled(const std::string& out_file, double t, double dt, const StepWatch& watch, const FastestCell& c);

// Throws when a step is not a positive finite number of at least absurd_step.
void check_step(const std::string& out_file, double t, double dt);

// Scans solver `s` (anything with state_row over grid `g`) and throws at the first bad
// cell, or when the volume is not finite.
template <class S>
void check_state(const S& s, const Grid& g, const std::string& out_file, double t, double volume_start) {
    std::vector<double> h(std::size_t(g.nx)), u(std::size_t(g.nx)), v(std::size_t(g.nx));
    const double volume = s.volume();
    for (int j = 0; j < g.ny; ++j) {
        s.state_row(j, 0, g.nx, h.data(), u.data(), v.data());
        if (const auto bad = check_row(g, j, 0, h.data(), u.data(), v.data(), g.nx))
            fail_bad_state(out_file, t, *bad, volume_start, volume);
    }
    if (!std::isfinite(volume))
        fail_bad_state(out_file, t, BadCell{0, 0, 0, 0, "volume", volume, "not finite"}, volume_start, volume);
}

// The step of solver `s`: when it is not a sane number, the state is scanned first so
// that the error names the cell that made it so.
template <class S>
void check_step(const S& s, const Grid& g, const std::string& out_file, double t, double dt, double volume_start) {
    if (std::isfinite(dt) && dt >= absurd_step) return;
    check_state(s, g, out_file, t, volume_start);
    check_step(out_file, t, dt);
}

}  // namespace flotsam::hydro
