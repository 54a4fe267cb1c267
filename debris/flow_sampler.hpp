// What the debris step asks of a flow (debris/dynamics.cpp, loads.cpp, contact.cpp):
// depth, velocity and material acceleration at a point and time, and a lower bound of
// the depth over a block of cells. FlowReader (debris/flow_reader.hpp) answers it from a
// stored flow file; another flow source (another model's output, an analytic flow for
// tests) implements the same calls.
//
// Positions are in the frame of grid() [m]. Sampling is const and thread-safe: many
// bodies sample one flow at once between the flow's loads.
#pragma once
#include "common/grid.hpp"
#include "debris/kernels.hpp"
#include "debris/time_kernels.hpp"

namespace flotsam::debris {

// Depth and velocity at a point.
struct FlowPoint {
    double depth = 0.0;  // h [m]
    double u = 0.0;      // [m/s]
    double v = 0.0;      // [m/s]
};

// Plus the material acceleration Du/Dt = ∂u/∂t + (u·∇)u of the same interpolant.
struct FlowPointAccel : FlowPoint {
    double du_dt = 0.0;  // [m/s²]
    double dv_dt = 0.0;  // [m/s²]
};

// Index ranges [i0, i1) × [j0, j1) of grid cells.
struct CellWindow {
    int i0 = 0, i1 = 0, j0 = 0, j1 = 0;
    bool contains(const CellWindow& w) const { return w.i0 >= i0 && w.i1 <= i1 && w.j0 >= j0 && w.j1 <= j1; }
    bool operator==(const CellWindow&) const = default;
};

class FlowSampler {
public:
    virtual ~FlowSampler() = default;

    // What sampling at time t needs of the time axis, worked out once for many points at
    // the same t. For stored frames, their weights (FlowReader: valid until it loads
    // other frames or moves its window).
    struct TimeStencil {
        double t = 0.0;             // the time sampled [s]
        double a = 0.0;             // linear: weight of frame k+1 [-]
        double inv_dt = 0.0;        // 1 / frame interval, 0 where the flow is held [1/s]
        bool cubic = false;         // the cubic interpolant is on (its guard is per node)
        TimeWeights cubic_weights;  // set where it is
    };

    // The flow's cells: what cells_for, covers and min_depth count in.
    virtual const Grid& grid() const = 0;
    virtual TimeStencil at_time(double t) const = 0;
    // Depth and velocity at the n points p[k], into out[k].
    virtual void sample(const Vec2* p, int n, const TimeStencil& ts, FlowPoint* out) const = 0;
    // Depth at the n points p[k], into out[k]: the depth the bodies float in and stand
    // on (over a ground finer than the flow, the flow's level carried down to it).
    virtual void depth(const Vec2* p, int n, const TimeStencil& ts, double* out) const = 0;
    // Depth (as depth()), velocity and material acceleration at (x, y) at time t.
    virtual FlowPointAccel sample_accel(double x, double y, double t) const = 0;
    // A lower bound of depth() anywhere inside cells w's stencils around the time
    // sampled: where it is not below a body's draft, no point under it touches the ground.
    virtual double min_depth(const CellWindow& w) const = 0;
    // Whether points whose stencils lie in cells w may be sampled now (a reader holds
    // only part of the grid).
    virtual bool covers(const CellWindow& w) const = 0;

    // One point: the same as the calls above for n = 1, to the bit.
    FlowPoint sample(double x, double y, double t) const { return sample(x, y, at_time(t)); }
    double depth(double x, double y, double t) const { return depth(x, y, at_time(t)); }
    FlowPoint sample(double x, double y, const TimeStencil& ts) const;
    double depth(double x, double y, const TimeStencil& ts) const;
    // The cells a box [x0, x1] × [y0, y1] needs for sampling (bilinear stencils included).
    CellWindow cells_for(double x0, double x1, double y0, double y1) const;

protected:
    FlowSampler() = default;
    FlowSampler(const FlowSampler&) = default;
    FlowSampler(FlowSampler&&) = default;
    FlowSampler& operator=(const FlowSampler&) = default;
    FlowSampler& operator=(FlowSampler&&) = default;
};

}  // namespace flotsam::debris
