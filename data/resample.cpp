#include "data/resample.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/checks.hpp"
#include "common/error.hpp"

namespace flotsam {

Grid grid_covering(double x_min, double x_max, double y_min, double y_max, double spacing) {
    check_range("--resolution", spacing, Range::positive("m"));
    const double nx = std::ceil((x_max - x_min) / spacing - 1e-6), ny = std::ceil((y_max - y_min) / spacing - 1e-6);
    // A scene holds some ten double fields per cell while it is built and written.
    check_allocation("--resolution", number_text(spacing) + " m", std::max(nx, 1.0) * std::max(ny, 1.0), 80.0, "cells");
    if (nx > 2e9 || ny > 2e9) fail("", "--resolution", std::to_string(spacing) + " m makes more than 2e9 cells along one side");
    Grid g;
    g.dx = g.dy = spacing;
    // The small slack keeps an extent that is a whole number of cells from gaining a sliver cell.
    g.nx = std::max(1, int(std::ceil((x_max - x_min) / spacing - 1e-6)));
    g.ny = std::max(1, int(std::ceil((y_max - y_min) / spacing - 1e-6)));
    g.x0 = x_min + 0.5 * spacing;
    g.y0 = y_min + 0.5 * spacing;
    return g;
}

namespace {

// Source cells and weights (summing to 1) that make one target cell along one axis.
struct Weights {
    std::vector<int> index;
    std::vector<double> weight;
};

std::vector<Weights> axis_weights(int n_from, double c0_from, double d_from, int n_to, double c0_to, double d_to) {
    std::vector<Weights> out(n_to);
    const bool average = d_to > d_from * (1.0 + 1e-9);
    const double lo_from = c0_from - 0.5 * d_from;
    for (int t = 0; t < n_to; ++t) {
        Weights& w = out[t];
        const double c = c0_to + t * d_to;
        if (average) {
            const double lo = c - 0.5 * d_to, hi = c + 0.5 * d_to;
            const int s0 = std::max(0, int(std::floor((lo - lo_from) / d_from)));
            const int s1 = std::min(n_from - 1, int(std::floor((hi - lo_from) / d_from)));
            double total = 0.0;
            for (int s = s0; s <= s1; ++s) {
                const double a = std::max(lo, lo_from + s * d_from), b = std::min(hi, lo_from + (s + 1) * d_from);
                if (b > a) {
                    w.index.push_back(s);
                    w.weight.push_back(b - a);
                    total += b - a;
                }
            }
            if (total <= 0.0) {
                w.index = {std::clamp(int(std::floor((c - lo_from) / d_from)), 0, n_from - 1)};
                w.weight = {1.0};
                continue;
            }
            for (double& v : w.weight) v /= total;
        } else {
            const double u = std::clamp((c - c0_from) / d_from, 0.0, double(n_from - 1));
            const int s = std::min(int(std::floor(u)), std::max(0, n_from - 2));
            const double f = u - s;
            w.index = {s};
            w.weight = {1.0 - f};
            if (n_from > 1) {
                w.index.push_back(s + 1);
                w.weight.push_back(f);
            }
        }
    }
    return out;
}

}  // namespace

std::vector<double> resample(const Grid& from, const std::vector<double>& field, const Grid& to) {
    if (from.nx == to.nx && from.ny == to.ny && std::abs(from.dx - to.dx) < 1e-12 && std::abs(from.dy - to.dy) < 1e-12 &&
        std::abs(from.x0 - to.x0) < 1e-9 && std::abs(from.y0 - to.y0) < 1e-9)
        return field;
    const auto wx = axis_weights(from.nx, from.x0, from.dx, to.nx, to.x0, to.dx);
    const auto wy = axis_weights(from.ny, from.y0, from.dy, to.ny, to.y0, to.dy);
    // Rows first (x), then columns (y): separable, so each pass is a short weighted sum.
    std::vector<double> rows(std::size_t(from.ny) * to.nx);
    for (int j = 0; j < from.ny; ++j)
        for (int i = 0; i < to.nx; ++i) {
            double s = 0.0;
            for (std::size_t k = 0; k < wx[i].index.size(); ++k) s += wx[i].weight[k] * field[from.index(wx[i].index[k], j)];
            rows[std::size_t(j) * to.nx + i] = s;
        }
    std::vector<double> out(to.size());
    for (int j = 0; j < to.ny; ++j)
        for (int i = 0; i < to.nx; ++i) {
            double s = 0.0;
            for (std::size_t k = 0; k < wy[j].index.size(); ++k)
                s += wy[j].weight[k] * rows[std::size_t(wy[j].index[k]) * to.nx + i];
            out[to.index(i, j)] = s;
        }
    return out;
}

}  // namespace flotsam
