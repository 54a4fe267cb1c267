// Finite or a named error: the checks a hydro run makes on its own state (issue 18).
//
// Before every stored frame and every checkpoint the whole state is scanned; the first
// cell whose depth or velocity is not finite, whose depth is negative or absurdly deep,
// or whose speed is absurd stops the run with the time, the cell, the variable and the
// volume, so a run never exits 0 with NaN in its fields and never writes them. A NaN
// does not shrink the CFL step (max() skips it), so the per-frame scan is what catches
// it; the step itself is checked every step.
#pragma once
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
