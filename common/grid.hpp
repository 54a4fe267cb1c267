// A uniform, cell-centred grid. Fields on it are row-major with x fastest, so a field
// index is j * nx + i and matches NetCDF's (y, x) and (time, y, x) layouts.
#pragma once
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace flotsam {

struct Grid {
    int nx = 0;       // cells along x (east)
    int ny = 0;       // cells along y (north)
    double x0 = 0.0;  // x of the centre of cell i = 0 [m]
    double y0 = 0.0;  // y of the centre of cell j = 0 [m]
    double dx = 1.0;  // cell size along x [m]
    double dy = 1.0;  // cell size along y [m]

    std::size_t size() const { return std::size_t(nx) * std::size_t(ny); }
    std::size_t index(int i, int j) const { return std::size_t(j) * std::size_t(nx) + std::size_t(i); }
    double x(int i) const { return x0 + i * dx; }
    double y(int j) const { return y0 + j * dy; }
    double x_min_edge() const { return x0 - 0.5 * dx; }
    double x_max_edge() const { return x0 + (nx - 0.5) * dx; }
    double y_min_edge() const { return y0 - 0.5 * dy; }
    double y_max_edge() const { return y0 + (ny - 0.5) * dy; }
    // Cell holding point (x, y), clamped to the grid.
    int cell_i(double x) const {
        int i = int(std::floor((x - x0) / dx + 0.5));
        return i < 0 ? 0 : (i >= nx ? nx - 1 : i);
    }
    int cell_j(double y) const {
        int j = int(std::floor((y - y0) / dy + 0.5));
        return j < 0 ? 0 : (j >= ny ? ny - 1 : j);
    }
    bool contains(double x, double y) const {
        return x >= x_min_edge() && x <= x_max_edge() && y >= y_min_edge() && y <= y_max_edge();
    }
    std::vector<double> xs() const {
        std::vector<double> v(nx);
        for (int i = 0; i < nx; ++i) v[i] = x(i);
        return v;
    }
    std::vector<double> ys() const {
        std::vector<double> v(ny);
        for (int j = 0; j < ny; ++j) v[j] = y(j);
        return v;
    }
};

// A grid from coordinate vectors; throws naming `file` and the coordinate when they are
// not uniform, not increasing, or too short.
Grid grid_from_coordinates(const std::vector<double>& x, const std::vector<double>& y, const std::string& file);

}  // namespace flotsam
