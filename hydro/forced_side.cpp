#include "hydro/forced_side.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "common/checks.hpp"
#include "common/error.hpp"

namespace flotsam::hydro {

namespace {

// Weights of the samples k-1 .. k+2 (index, weight) for the value at t, with
// time[k] <= t <= time[k+1].
using TimeWeights = std::array<std::pair<std::size_t, double>, 4>;

TimeWeights linear_weights(const std::vector<double>& time, std::size_t k, double t) {
    if (k + 1 >= time.size()) return {{{k, 1.0}, {k, 0.0}, {k, 0.0}, {k, 0.0}}};
    const double s = (t - time[k]) / (time[k + 1] - time[k]);
    return {{{k, 1.0 - s}, {k + 1, s}, {k, 0.0}, {k, 0.0}}};
}

// The slope at sample k as weights on the samples: the parabola's through k-1, k, k+1,
// a secant at the ends.
std::array<std::pair<std::size_t, double>, 3> slope_weights(const std::vector<double>& time, std::size_t k) {
    const std::size_t n = time.size();
    if (k == 0) {
        const double d = time[1] - time[0];
        return {{{0, -1.0 / d}, {1, 1.0 / d}, {0, 0.0}}};
    }
    if (k == n - 1) {
        const double d = time[n - 1] - time[n - 2];
        return {{{n - 2, -1.0 / d}, {n - 1, 1.0 / d}, {0, 0.0}}};
    }
    const double before = time[k] - time[k - 1], after = time[k + 1] - time[k];
    const double a = before / (before + after), b = after / (before + after);  // of the secants after and before
    return {{{k - 1, -b / before}, {k, b / before - a / after}, {k + 1, a / after}}};
}

std::vector<std::pair<std::size_t, double>> cubic_weights(const std::vector<double>& time, std::size_t k, double t) {
    if (k + 1 >= time.size()) return {{k, 1.0}};
    const double h = time[k + 1] - time[k], s = (t - time[k]) / h;
    const double h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s), h01 = s * s * (3 - 2 * s),
                 h11 = s * s * (s - 1);
    std::vector<std::pair<std::size_t, double>> w{{k, h00}, {k + 1, h01}};
    for (const auto& [i, m] : slope_weights(time, k)) w.push_back({i, h10 * h * m});
    for (const auto& [i, m] : slope_weights(time, k + 1)) w.push_back({i, h11 * h * m});
    return w;
}

}  // namespace

ForcedSide::ForcedSide(std::shared_ptr<const SideRecord> record, const std::vector<double>& cell_along, double cell_size,
                       ForcingTime time, const std::string& side)
    : record_(std::move(record)), time_(time) {
    const SideRecord& r = *record_;
    const std::string what = "boundary " + side;
    if (r.time.size() < 2) fail(r.source, what, "needs at least two times");
    if (r.along.empty()) fail(r.source, what, "no points along the side");
    const std::size_t n = r.points();
    if (r.level.size() != r.time.size() * n || (r.has_velocity() && (r.u.size() != r.level.size() || r.v.size() != r.level.size())) ||
        (r.has_depth() && r.depth.size() != r.level.size()))
        fail(r.source, what, "values do not match its times and points");
    const double tolerance = 0.5 * cell_size * (1.0 + 1e-9);
    for (double a : cell_along) {
        if (a < r.along.front() - tolerance || a > r.along.back() + tolerance)
            fail(r.source, what,
                 "does not cover the side: its points span " + number_text(r.along.front()) + " to " +
                     number_text(r.along.back()) + " m along it, the side's cells " + number_text(cell_along.front()) +
                     " to " + number_text(cell_along.back()) + " m");
        const auto it = std::upper_bound(r.along.begin(), r.along.end(), a);
        const std::size_t p = it == r.along.begin() ? 0 : std::size_t(it - r.along.begin()) - 1;
        double w = 0.0;
        if (p + 1 < n) w = std::clamp((a - r.along[p]) / (r.along[p + 1] - r.along[p]), 0.0, 1.0);
        point_.push_back(p);
        weight_.push_back(w);
    }
}

double ForcedSide::max_level() const {
    const auto& v = record_->level;
    return *std::max_element(v.begin(), v.end());
}

void ForcedSide::sample(double t, std::vector<double>& level, std::vector<double>& u, std::vector<double>& v,
                        std::vector<double>& depth) const {
    const SideRecord& r = *record_;
    t = std::clamp(t, r.time.front(), r.time.back());
    const auto it = std::upper_bound(r.time.begin(), r.time.end(), t);
    const std::size_t k = std::min(std::size_t(it - r.time.begin()) - 1, r.time.size() - 2);
    std::vector<std::pair<std::size_t, double>> w;
    if (time_ == ForcingTime::cubic)
        w = cubic_weights(r.time, k, t);
    else
        for (const auto& p : linear_weights(r.time, k, t)) w.push_back(p);
    const std::size_t n = r.points(), cells = point_.size();
    // The record's points at t, then along the side to each cell.
    auto at_cells = [&](const std::vector<double>& series, std::vector<double>& out) {
        std::vector<double>& now = points_now_;
        now.assign(n, 0.0);
        for (const auto& [i, wi] : w)
            if (wi != 0.0)
                for (std::size_t p = 0; p < n; ++p) now[p] += wi * series[i * n + p];
        out.resize(cells);
        for (std::size_t c = 0; c < cells; ++c) {
            const std::size_t p = point_[c];
            out[c] = weight_[c] == 0.0 ? now[p] : (1.0 - weight_[c]) * now[p] + weight_[c] * now[p + 1];
        }
    };
    at_cells(r.level, level);
    if (r.has_velocity()) {
        at_cells(r.u, u);
        at_cells(r.v, v);
    } else {
        u.clear();
        v.clear();
    }
    if (r.has_depth())
        at_cells(r.depth, depth);
    else
        depth.clear();
}

void forced_ghost(double h_in, double un_in, double ut_in, double h_given, double un_given, double ut_given, double g,
                  double& h_out, double& un_out, double& ut_out) {
    const double incoming = un_given + 2.0 * std::sqrt(g * std::max(h_given, 0.0));
    const double outgoing = un_in - 2.0 * std::sqrt(g * std::max(h_in, 0.0));
    const double c_b = std::max(0.0, 0.25 * (incoming - outgoing));
    h_out = c_b * c_b / g;
    un_out = h_out > 0.0 ? 0.5 * (incoming + outgoing) : 0.0;
    ut_out = un_out > 0.0 ? ut_given : ut_in;
}

}  // namespace flotsam::hydro
