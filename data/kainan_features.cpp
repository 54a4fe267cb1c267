#include "data/kainan_features.hpp"

#include <cmath>

namespace flotsam {

namespace {

using Line = std::vector<std::array<double, 2>>;

// The band within `half_width` of a polyline, as one polygon: the line offset to its left
// and back along its right, the offsets of neighbouring segments meeting at their mitre
// (the line's turns are gentle, so the polygon is simple) [m].
std::vector<std::array<double, 2>> band_around(const Line& line, double half_width) {
    const std::size_t n = line.size();
    std::vector<std::array<double, 2>> left(n), right(n);
    const auto unit_normal = [&](std::size_t k) {  // of segment k → k + 1, to its left
        const double dx = line[k + 1][0] - line[k][0], dy = line[k + 1][1] - line[k][1], l = std::hypot(dx, dy);
        return std::array<double, 2>{-dy / l, dx / l};
    };
    for (std::size_t k = 0; k < n; ++k) {
        const auto a = unit_normal(k == 0 ? 0 : k - 1), b = unit_normal(k + 1 < n ? k : k - 1);
        // The mitre, the point on both neighbouring offset lines: along a + b, at
        // half_width / ((a + b) · a) of it.
        const double cx = a[0] + b[0], cy = a[1] + b[1], scale = half_width / (cx * a[0] + cy * a[1]);
        left[k] = {line[k][0] + scale * cx, line[k][1] + scale * cy};
        right[k] = {line[k][0] - scale * cx, line[k][1] - scale * cy};
    }
    std::vector<std::array<double, 2>> polygon(left);
    polygon.insert(polygon.end(), right.rbegin(), right.rend());
    return polygon;
}

// The channels of the measured layout (the DEM `flotsam scene import` reads,
// ../shared/data/city-topography-from-figure.nc), their lines through the lowest ground of
// the 1 cm import on cross-sections 5 cm apart (docs/scene.md, "Points, sections, regions"): Channel A from
// the basin's north-east arm north along x ≈ 4.4 m, then east-south-east from (4.75, −1.35);
// Channel B the trench from the basin's south-east corner to (4.70, −3.34).
const Line measured_channel_a = {{4.00, -1.90}, {4.40, -1.86}, {4.45, -1.52}, {4.58, -1.40}, {4.78, -1.35},
                                 {4.90, -1.38}, {5.30, -1.63}, {5.45, -1.74}, {5.65, -1.74}};
const Line measured_channel_b = {{3.75, -2.975}, {4.70, -3.34}};
// Each region holds the channel and its banks within this distance of its line, the width
// the regions of the generated scene have [m].
constexpr double channel_half_width = 0.10;

}  // namespace

SceneFeatures kainan_features(KainanLayout layout) {
    SceneFeatures f;
    // FD lies along the north quay (heading 0: long axis east-west, the basin's axis);
    // LD lies along the east-west street it stands on (heading 0 as well).
    f.points = {
        {"WG1", "gauge", -11.9, -2.0, 0.0},
        {"WG2", "gauge", -0.3, -3.0, 0.0},
        {"FD", "start", 1.37, -2.15, 0.0},
        {"LD", "start", 2.94, -1.26, 0.0},
    };
    // FD: the paper's first section at x = 1.8, then the middle and east end of the basin.
    // LD: across the streets of the building group east of the start (x = 3.3) and past
    // it (x = 3.8). channel_a_x4.6: across Channel A's north-east leg.
    f.sections = {
        {"fd_x1.8", 1.8, -2.70, -2.00}, {"fd_x2.6", 2.6, -2.70, -2.00}, {"fd_x3.4", 3.4, -3.00, -2.00},
        {"ld_x3.3", 3.3, -2.00, -0.80}, {"ld_x3.8", 3.8, -2.00, -0.80}, {"channel_a_x4.6", 4.6, -1.75, -1.30},
    };
    f.regions = {
        {"channel_a",
         {{4.00, -2.00}, {4.30, -1.90}, {4.85, -1.45}, {5.30, -1.66}, {5.30, -1.44}, {4.78, -1.24}, {4.26, -1.70}, {4.00, -1.80}}},
        {"channel_b", {{3.75, -2.70}, {3.90, -2.56}, {5.10, -3.55}, {4.95, -3.70}}},
        {"station_area", {{4.90, -1.45}, {5.80, -1.45}, {5.80, -0.95}, {4.90, -0.95}}},
        {"basin", {{0.90, -2.05}, {3.75, -2.05}, {3.75, -2.97}, {3.20, -2.97}, {3.00, -2.65}, {0.90, -2.65}}},
    };
    if (layout == KainanLayout::measured) {
        f.regions[0].polygon = band_around(measured_channel_a, channel_half_width);
        f.regions[1].polygon = band_around(measured_channel_b, channel_half_width);
    }
    return f;
}

std::vector<ManningRule> kainan_manning() {
    return {ManningRule{0.025, std::nullopt, -0.66, {}, {}}, ManningRule{0.013, {}, {}, {}, {}}};
}

std::string kainan_hydro_defaults() { return "output-window = -1,8.1,-4.1,0\nnest-x = -1.2\nnest-ratio = 4\n"; }

bool matches_kainan_extent(const Grid& g) {
    const double tol_x = g.dx, tol_y = g.dy;
    return std::abs(g.x_min_edge() - kainan_x_min_edge) <= tol_x && std::abs(g.x_max_edge() - kainan_x_max_edge) <= tol_x &&
           std::abs(g.y_min_edge() - kainan_y_min_edge) <= tol_y && std::abs(g.y_max_edge() - kainan_y_max_edge) <= tol_y;
}

void apply_features(Scene& scene, const SceneFeatures& f) {
    scene.points = f.points;
    scene.sections = f.sections;
    scene.regions = f.regions;
}

}  // namespace flotsam
