#include "common/grid.hpp"

#include <string>

#include "common/error.hpp"

namespace flotsam {

namespace {
// Spacing of a coordinate vector; uniform to 1e-6 of a cell (coordinates written as
// float or rounded decimals are accepted, real irregular grids are not).
double uniform_spacing(const std::vector<double>& c, const std::string& file, const char* name) {
    if (c.size() < 2)
        fail(file, std::string("coordinate '") + name + "'", "needs at least 2 values, has " + std::to_string(c.size()));
    for (std::size_t k = 0; k < c.size(); ++k)
        if (!std::isfinite(c[k]))
            fail(file, std::string("coordinate '") + name + "'", "value " + std::to_string(k) + " is not finite");
    const double d = (c.back() - c.front()) / double(c.size() - 1);
    if (!(d > 0)) fail(file, std::string("coordinate '") + name + "'", "must increase monotonically");
    for (std::size_t k = 1; k < c.size(); ++k) {
        const double step = c[k] - c[k - 1];
        if (!(step > 0))
            fail(file, std::string("coordinate '") + name + "'", "not monotonically increasing at index " + std::to_string(k));
        const double expected = c.front() + d * double(k);
        if (std::abs(c[k] - expected) > 1e-3 * d)
            fail(file, std::string("coordinate '") + name + "'",
                 "not uniformly spaced: value " + std::to_string(k) + " is " + std::to_string(c[k]) + ", expected " +
                     std::to_string(expected) + " for spacing " + std::to_string(d));
    }
    return d;
}
}  // namespace

Grid grid_from_coordinates(const std::vector<double>& x, const std::vector<double>& y, const std::string& file) {
    Grid g;
    g.dx = uniform_spacing(x, file, "x");
    g.dy = uniform_spacing(y, file, "y");
    g.nx = int(x.size());
    g.ny = int(y.size());
    g.x0 = x.front();
    g.y0 = y.front();
    return g;
}

}  // namespace flotsam
