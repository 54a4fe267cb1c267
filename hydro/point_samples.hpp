// The flow at a point between cell centres, as the gauges and the boundary output read
// it: bilinear between the four cell centres around the point (at a cell centre, that
// cell alone), so a point reads the flow where it stands, not at the nearest centre up to
// half a cell away. Depth and velocities are interpolated over the four cells (a dry one
// counts as h = u = v = 0); the level over the wet ones only (a dry cell's "level" is its
// ground), and where all four are dry it is the interpolated ground.
#pragma once
#include <algorithm>
#include <cmath>

#include "common/grid.hpp"

namespace flotsam::hydro {

struct PointSample {
    double eta, h, u, v;  // level [m], depth [m], velocity [m s-1]
};

// Along each axis: the cell centre at or before the point (the last but one at the far
// edge) and the weight of the next one, in [0, 1].
struct PointStencil {
    int i = 0, j = 0;
    double wx = 0.0, wy = 0.0;
};

inline PointStencil point_stencil(const Grid& g, double x, double y) {
    auto axis = [](double p, double first_centre, double spacing, int n, int& i, double& w) {
        if (n < 2) return;
        const double f = (p - first_centre) / spacing;
        i = std::clamp(int(std::floor(f)), 0, n - 2);
        w = std::clamp(f - double(i), 0.0, 1.0);
    };
    PointStencil s;
    axis(x, g.x(0), g.dx, g.nx, s.i, s.wx);
    axis(y, g.y(0), g.dy, g.ny, s.j, s.wy);
    return s;
}

// `s` offers depth, level, x_velocity and y_velocity at (i, j) (hydro/run_solver.hpp, RunnableSolver).
template <class S>
PointSample sample_point(const S& s, const PointStencil& p) {
    PointSample g{0.0, 0.0, 0.0, 0.0};
    double wet_weight = 0.0, wet_level = 0.0, ground = 0.0;
    for (int b = 0; b < 2; ++b)
        for (int a = 0; a < 2; ++a) {
            const double w = (a ? p.wx : 1.0 - p.wx) * (b ? p.wy : 1.0 - p.wy);
            if (w == 0.0) continue;
            const int i = p.i + a, j = p.j + b;
            const double h = s.depth(i, j);
            g.h += w * h;
            g.u += w * s.x_velocity(i, j);
            g.v += w * s.y_velocity(i, j);
            ground += w * (s.level(i, j) - h);
            if (h > 0.0) {
                wet_weight += w;
                wet_level += w * s.level(i, j);
            }
        }
    g.eta = wet_weight > 0.0 ? wet_level / wet_weight : ground;
    return g;
}

}  // namespace flotsam::hydro
