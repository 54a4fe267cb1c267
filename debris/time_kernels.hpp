// Pure kernels of the flow reader's interpolation in time (debris/flow_reader.*): the
// weights that turn the stored frames around t into a value and its time derivative.
//
// Linear: f(t) = (1 − s) f_k + s f_(k+1), s = (t − t_k)/Δ, Δ = t_(k+1) − t_k.
//
// Cubic (Catmull-Rom, the cubic Hermite with finite-difference slopes): on [t_k, t_(k+1)]
//   f(s) = h00(s) f_k + h01(s) f_(k+1) + Δ (h10(s) m_k + h11(s) m_(k+1)),
//   m_k = (f_(k+1) − f_(k−1)) / (t_(k+1) − t_(k−1)),  m_(k+1) = (f_(k+2) − f_k) / (t_(k+2) − t_k),
//   h00 = 2s³ − 3s² + 1,  h10 = s³ − 2s² + s,  h01 = −2s³ + 3s²,  h11 = s³ − s².
// Collected per frame with c0 = Δ/(t_(k+1) − t_(k−1)) and c1 = Δ/(t_(k+2) − t_k):
//   w_(k−1) = −c0 h10,  w_k = h00 − c1 h11,  w_(k+1) = h01 + c0 h10,  w_(k+2) = c1 h11.
// The weights sum to 1 (a steady field is exact) and a field linear in t is exact at
// any frame spacing. At the first and last interval the missing frame is the nearest one
// (k−1 → k, k+2 → k+1), which makes that slope one-sided. With two frames only, both
// slopes are the secant and the cubic is the linear interpolant. The time derivative
// uses the same frames with the s-derivatives of the h's over Δ, so it is the derivative
// of the value (Du/Dt stays consistent with the interpolant).
//
// A cubic can undershoot (below zero at a wetting front, below both frames in a trough);
// the reader checks each node with `cubic_depth_admissible` and uses the linear weights,
// for depth and discharge alike, where it fails.
#pragma once

namespace flotsam::debris {

// Linear: value and d/dt from the two frames around t. s: position in the interval,
// 0..1 [-]; inv_dt: 1/Δ, or 0 where the flow is held steady [1/s].
inline double linear_in_time(double s, double f_k, double f_k1) { return (1.0 - s) * f_k + s * f_k1; }
inline double linear_rate(double inv_dt, double f_k, double f_k1) { return (f_k1 - f_k) * inv_dt; }

// Cubic: value and d/dt weights of the four frames k−1, k, k+1, k+2 (in that order)
// [-], [1/s].
struct TimeWeights {  // set in full by catmull_rom_time_weights
    double w[4];
    double dw[4];
};

// c0 = Δ/(t_(k+1) − t_(k−1)), c1 = Δ/(t_(k+2) − t_k) [-] (1 where the frame is missing).
inline TimeWeights catmull_rom_time_weights(double s, double inv_dt, double c0, double c1) {
    const double s2 = s * s, s3 = s2 * s;
    const double h00 = 2.0 * s3 - 3.0 * s2 + 1.0, h10 = s3 - 2.0 * s2 + s, h01 = -2.0 * s3 + 3.0 * s2, h11 = s3 - s2;
    const double d00 = 6.0 * s2 - 6.0 * s, d10 = 3.0 * s2 - 4.0 * s + 1.0, d01 = -d00, d11 = 3.0 * s2 - 2.0 * s;
    TimeWeights tw;
    tw.w[0] = -c0 * h10;
    tw.w[1] = h00 - c1 * h11;
    tw.w[2] = h01 + c0 * h10;
    tw.w[3] = c1 * h11;
    tw.dw[0] = -c0 * d10 * inv_dt;
    tw.dw[1] = (d00 - c1 * d11) * inv_dt;
    tw.dw[2] = (d01 + c0 * d10) * inv_dt;
    tw.dw[3] = c1 * d11 * inv_dt;
    return tw;
}

// Σ w_r f_r over the four frames (w: the weights or their d/dt).
inline double apply_time_weights(const double (&w)[4], double f0, double f1, double f2, double f3) {
    return w[0] * f0 + w[1] * f1 + w[2] * f2 + w[3] * f3;
}

// The guard of the cubic depth at one node (h: the four frames' depths there [m]). The
// cubic is used only where
//  * it is not below the shallower of the two frames around t (but for round-off of a
//    steady depth): so it is never negative,
//    and the smallest stored depth of those two frames stays a lower bound of the
//    interpolated depth (the reader's min_depth relies on it); an overshoot above the
//    deeper frame (a peak between frames) is kept, that is what the cubic is for;
//  * all four frames are wet (≥ dry_depth [m]): at a wetting or drying front the linear
//    interpolant keeps u = q/h a depth-weighted mean of the stored velocities.
inline bool cubic_depth_admissible(double cubic_depth, const double (&h)[4], double dry_depth) {
    const double lo = h[1] < h[2] ? h[1] : h[2];
    return cubic_depth >= lo * (1.0 - 1e-12) && lo >= dry_depth && h[0] >= dry_depth && h[3] >= dry_depth;
}

}  // namespace flotsam::debris
