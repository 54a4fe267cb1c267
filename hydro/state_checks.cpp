#include "hydro/state_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/error.hpp"

namespace flotsam::hydro {

std::optional<BadCell> check_row(const Grid& g, int j, int i0, const double* h, const double* u, const double* v, int n) {
    for (int k = 0; k < n; ++k) {
        const int i = i0 + k;
        auto bad = [&](const char* variable, double value, const char* why) {
            return BadCell{i, j, g.x(i), g.y(j), variable, value, why};
        };
        if (!std::isfinite(h[k])) return bad("depth h", h[k], "not finite");
        if (!std::isfinite(u[k])) return bad("x velocity u", u[k], "not finite");
        if (!std::isfinite(v[k])) return bad("y velocity v", v[k], "not finite");
        if (h[k] < negative_depth_tolerance) return bad("depth h", h[k], "negative");
        if (h[k] > absurd_depth) return bad("depth h", h[k], "deeper than any ocean (11 km)");
        const double speed = std::sqrt(u[k] * u[k] + v[k] * v[k]);
        if (speed > absurd_speed) return bad("speed", speed, "faster than 1000 m/s");
    }
    return std::nullopt;
}

void fail_bad_state(const std::string& out_file, double t, const BadCell& c, double volume_start, double volume_now) {
    char buf[512];
    if (c.variable == "volume")
        std::snprintf(buf, sizeof buf, "at t = %.6g s the water volume is %g m^3 (%.6g at the start)", t, volume_now, volume_start);
    else
        std::snprintf(buf, sizeof buf,
                      "at t = %.6g s, cell (i %d, j %d) at x = %.6g m, y = %.6g m: %s = %g is %s (volume %.6g -> %g m^3)", t, c.i,
                      c.j, c.x, c.y, c.variable.c_str(), c.value, c.why.c_str(), volume_start, volume_now);
    fail(out_file, "",
         std::string("the run stopped: ") + buf +
             "; no flow file was written. Check the boundary series, --manning-n and the step settings "
             "(--cfl, --max-dt, --courant)");
}

bool StepWatch::stalled(double dt) {
    if (!(dt > 0.0)) return false;  // check_step names it
    const int bin = std::clamp(int(std::floor((std::log10(dt) + 15.0) * 100.0)), 0, kBins - 1);
    const bool below = count_ > collapse_steps && dt < collapse_ratio * median();
    ++bins_[std::size_t(bin)];
    ++count_;
    below_ = below ? below_ + 1 : 0;
    return below_ > collapse_steps;
}

double StepWatch::median() const {
    long seen = 0;
    for (int b = 0; b < kBins; ++b) {
        seen += bins_[std::size_t(b)];
        if (2 * seen >= count_) return std::pow(10.0, (b + 0.5) / 100.0 - 15.0);
    }
    return 0.0;
}

void fail_stalled(const std::string& out_file, double t, double dt, const StepWatch& watch, const FastestCell& c) {
    char buf[640];
    std::snprintf(buf, sizeof buf,
                  "at t = %.6g s the time step collapsed to %.3g s, below %g of the run's median step (%.3g s) for %d steps. "
                  "The fastest water sets it: cell (i %d, j %d) at x = %.6g m, y = %.6g m, depth %.3g m, speed %.3g m/s, bed "
                  "%.6g m (CFL rate %.3g 1/s)",
                  t, dt, collapse_ratio, watch.median(), watch.steps_below(), c.i, c.j, c.x, c.y, c.depth, c.speed, c.bed, c.rate);
    fail(out_file, "",
         std::string("the run stopped: ") + buf +
             "; no flow file was written. A film racing over dry ground or a wave trapped in a few cells does this: check the "
             "scene's ground and the boundary series there, or run with a larger --dry-depth");
}

void check_step(const std::string& out_file, double t, double dt) {
    if (std::isfinite(dt) && dt >= absurd_step) return;
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "at t = %.6g s the stable time step is %g s (not a number of at least %g s: the state is absurd)", t, dt,
                  absurd_step);
    fail(out_file, "", std::string("the run stopped: ") + buf + "; no flow file was written");
}

}  // namespace flotsam::hydro
