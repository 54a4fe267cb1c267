// Small pure functions on sampled trajectories and samples, shared by the sweep summary
// and the statistics (sweep/sweep_stats.cpp). Definitions in docs/sweep.md.
#pragma once
#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

namespace flotsam::sweep {

// A body counts as moving once its centre is this far from its start [m] (for the
// paper's 0.25 m box; body_scale() scales it for other bodies).
inline constexpr double motion_threshold = 0.005;

// The thresholds of the statistics that are lengths or speeds hold for the paper's
// 0.25 m box; for a body of length L they follow Froude's law with s = L / 0.25 m:
// lengths x s, speeds and times x sqrt(s). Exactly 1 for the paper's box.
inline double body_scale(double length) { return length / 0.25; }

// Index of the first sample at least `threshold` from the first one; -1 when none.
inline int motion_start_index(const std::vector<double>& x, const std::vector<double>& y, double threshold = motion_threshold) {
    for (std::size_t k = 0; k < x.size(); ++k)
        if (std::hypot(x[k] - x[0], y[k] - y[0]) >= threshold) return int(k);
    return -1;
}

// Sum of the straight segments between samples [m].
inline double path_length(const std::vector<double>& x, const std::vector<double>& y) {
    double s = 0.0;
    for (std::size_t k = 1; k < x.size(); ++k) s += std::hypot(x[k] - x[k - 1], y[k] - y[k - 1]);
    return s;
}

// The first crossing of the line x = xs between samples (either direction), with y in
// [y_min, y_max]; time, y and speed linearly interpolated between the two samples.
struct Passage {
    double time = 0.0;   // [s]
    double y = 0.0;      // [m]
    double speed = 0.0;  // |(u, v)| interpolated [m/s]
};
inline std::optional<Passage> first_passage(const std::vector<double>& t, const std::vector<double>& x,
                                            const std::vector<double>& y, const std::vector<double>& u,
                                            const std::vector<double>& v, double xs, double y_min, double y_max) {
    for (std::size_t k = 1; k < x.size(); ++k) {
        const double a = x[k - 1] - xs, b = x[k] - xs;
        if (a == 0.0 && b == 0.0) continue;
        if ((a < 0) == (b < 0) && a != 0.0 && b != 0.0) continue;
        if (a == 0.0 && k > 1) continue;  // counted as the end of the previous segment
        const double w = a / (a - b);     // fraction of the segment at the crossing
        const double yc = y[k - 1] + w * (y[k] - y[k - 1]);
        if (yc < y_min || yc > y_max) continue;
        const double uc = u[k - 1] + w * (u[k] - u[k - 1]), vc = v[k - 1] + w * (v[k] - v[k - 1]);
        return Passage{t[k - 1] + w * (t[k] - t[k - 1]), yc, std::hypot(uc, vc)};
    }
    return std::nullopt;
}

// Wraps an angle to (−180, 180] [degree].
inline double wrap_deg(double a) {
    a = std::fmod(a, 360.0);
    if (a <= -180.0) a += 360.0;
    if (a > 180.0) a -= 360.0;
    return a;
}

// Samples k0 ≤ k with t[k] ≤ t[k0] + window: the rotation yaw[k] − yaw[k0] (unwrapped,
// counter-clockwise positive) of largest magnitude [degree].
inline double max_rotation(const std::vector<double>& t, const std::vector<double>& yaw_deg, int k0, double window) {
    double best = 0.0;
    for (std::size_t k = std::size_t(k0); k < t.size() && t[k] <= t[std::size_t(k0)] + window + 1e-9; ++k) {
        const double r = yaw_deg[k] - yaw_deg[std::size_t(k0)];
        if (std::fabs(r) > std::fabs(best)) best = r;
    }
    return best;
}

// Angle of the long axis against the direction of motion, folded to (−90, 90] (a box
// looks the same turned by 180°): positive when the axis lies counter-clockwise of the
// velocity [degree].
inline double yaw_to_motion(double yaw_deg, double u, double v) {
    double a = wrap_deg(yaw_deg - std::atan2(v, u) * 180.0 / std::numbers::pi);
    if (a > 90.0) a -= 180.0;
    if (a <= -90.0) a += 180.0;
    return a;
}

// Over the window as in max_rotation, at samples faster than min_speed: the yaw against
// the direction of motion of largest magnitude [degree]; NaN when no sample qualifies.
inline double max_yaw_to_motion(const std::vector<double>& t, const std::vector<double>& yaw_deg, const std::vector<double>& u,
                                const std::vector<double>& v, int k0, double window, double min_speed) {
    double best = std::nan("");
    for (std::size_t k = std::size_t(k0); k < t.size() && t[k] <= t[std::size_t(k0)] + window + 1e-9; ++k) {
        if (std::hypot(u[k], v[k]) < min_speed) continue;
        const double a = yaw_to_motion(yaw_deg[k], u[k], v[k]);
        if (std::isnan(best) || std::fabs(a) > std::fabs(best)) best = a;
    }
    return best;
}

// Direction of the straight line from the first sample to the position at time te
// (linear between samples), from +x (east) counter-clockwise in (−180, 180] [degree]:
// positive north of east, so north-east is positive and south-east negative, as the
// paper's Fig. 16c plots it. NaN when that position is less than `min_distance` from the
// first sample (no direction yet).
inline double movement_direction(const std::vector<double>& t, const std::vector<double>& x, const std::vector<double>& y,
                                 double te, double min_distance = motion_threshold);

// Pearson's correlation coefficient of the pairs (a_k, b_k) in which both are defined
// (not NaN); NaN with fewer than two such pairs or when either side does not vary.
inline double pearson_correlation(const std::vector<double>& a, const std::vector<double>& b) {
    double n = 0, sa = 0, sb = 0;
    for (std::size_t k = 0; k < a.size(); ++k)
        if (!std::isnan(a[k]) && !std::isnan(b[k])) {
            n += 1;
            sa += a[k];
            sb += b[k];
        }
    if (n < 2) return std::nan("");
    const double ma = sa / n, mb = sb / n;
    double cab = 0, caa = 0, cbb = 0;
    for (std::size_t k = 0; k < a.size(); ++k)
        if (!std::isnan(a[k]) && !std::isnan(b[k])) {
            cab += (a[k] - ma) * (b[k] - mb);
            caa += (a[k] - ma) * (a[k] - ma);
            cbb += (b[k] - mb) * (b[k] - mb);
        }
    if (!(caa > 0) || !(cbb > 0)) return std::nan("");
    return cab / std::sqrt(caa * cbb);
}

// Value at time tq of a sampled series (linear; held beyond the ends).
inline double sample_at(const std::vector<double>& t, const std::vector<double>& f, double tq) {
    if (tq <= t.front()) return f.front();
    if (tq >= t.back()) return f.back();
    const std::size_t k = std::size_t(std::upper_bound(t.begin(), t.end(), tq) - t.begin());
    const double w = (tq - t[k - 1]) / (t[k] - t[k - 1]);
    return f[k - 1] + w * (f[k] - f[k - 1]);
}

inline double movement_direction(const std::vector<double>& t, const std::vector<double>& x, const std::vector<double>& y,
                                 double te, double min_distance) {
    const double dx = sample_at(t, x, te) - x.front(), dy = sample_at(t, y, te) - y.front();
    if (std::hypot(dx, dy) < min_distance) return std::nan("");
    return std::atan2(dy, dx) * 180.0 / std::numbers::pi;
}

// Quantile q of sorted values, linear between order statistics (Hyndman & Fan type 7).
inline double quantile_sorted(const std::vector<double>& s, double q) {
    if (s.empty()) return std::nan("");
    const double h = (double(s.size()) - 1.0) * q;
    const std::size_t lo = std::size_t(std::floor(h));
    const std::size_t hi = std::min(lo + 1, s.size() - 1);
    return s[lo] + (h - double(lo)) * (s[hi] - s[lo]);
}

inline double mean_of(const std::vector<double>& v) {
    double s = 0.0;
    for (double a : v) s += a;
    return v.empty() ? std::nan("") : s / double(v.size());
}

// Sample standard deviation (n − 1 in the denominator); 0 for one value.
inline double std_of(const std::vector<double>& v) {
    if (v.size() < 2) return v.empty() ? std::nan("") : 0.0;
    const double m = mean_of(v);
    double s = 0.0;
    for (double a : v) s += (a - m) * (a - m);
    return std::sqrt(s / double(v.size() - 1));
}

// Silverman's rule of thumb: h = 0.9 min(σ, IQR/1.34) n^(−1/5); σ alone when the IQR is
// zero; when the values do not spread at all, 10 % of |mean| but at least `floor`.
inline double silverman_bandwidth(std::vector<double> v, double floor) {
    if (v.empty()) return std::nan("");
    std::sort(v.begin(), v.end());
    const double sigma = std_of(v);
    const double iqr = quantile_sorted(v, 0.75) - quantile_sorted(v, 0.25);
    double spread = iqr > 0 ? std::min(sigma, iqr / 1.34) : sigma;
    if (!(spread > 0)) return std::max(0.1 * std::fabs(mean_of(v)), floor);
    return 0.9 * spread * std::pow(double(v.size()), -0.2);
}

// Gaussian kernel density estimate at s: (1 / n h) Σ φ((s − v_i) / h).
inline double gaussian_kde(const std::vector<double>& v, double h, double s) {
    if (v.empty()) return 0.0;
    double sum = 0.0;
    for (double a : v) {
        const double z = (s - a) / h;
        sum += std::exp(-0.5 * z * z);
    }
    return sum / (double(v.size()) * h * std::sqrt(2.0 * std::numbers::pi));
}

}  // namespace flotsam::sweep
