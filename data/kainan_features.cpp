#include "data/kainan_features.hpp"

#include <cmath>

namespace flotsam {

SceneFeatures kainan_features() {
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
