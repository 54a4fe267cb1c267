// The calls every flow sampler shares, built on its own (debris/flow_sampler.hpp).
#include "debris/flow_sampler.hpp"

#include <algorithm>
#include <cmath>

namespace flotsam::debris {

FlowPoint FlowSampler::sample(double x, double y, const TimeStencil& ts) const {
    FlowPoint out;
    const Vec2 p{x, y};
    sample(&p, 1, ts, &out);
    return out;
}

double FlowSampler::depth(double x, double y, const TimeStencil& ts) const {
    double h = 0.0;
    const Vec2 p{x, y};
    depth(&p, 1, ts, &h);
    return h;
}

CellWindow FlowSampler::cells_for(double x0, double x1, double y0, double y1) const {
    // The bilinear stencil of x uses nodes floor(fx) and floor(fx) + 1.
    const Grid& g = grid();
    const Double4 f = Double4{x0 - g.x0, x1 - g.x0, y0 - g.y0, y1 - g.y0} / Double4{g.dx, g.dx, g.dy, g.dy};
    const int i0 = int(std::floor(f[0])), i1 = int(std::floor(f[1])) + 2;
    const int j0 = int(std::floor(f[2])), j1 = int(std::floor(f[3])) + 2;
    return CellWindow{std::clamp(i0, 0, g.nx - 2), std::clamp(i1, 2, g.nx), std::clamp(j0, 0, g.ny - 2), std::clamp(j1, 2, g.ny)};
}

}  // namespace flotsam::debris
