#include "data/manning.hpp"

namespace flotsam {

std::vector<double> manning_field(const Grid& g, const std::vector<ManningRule>& rules) {
    if (rules.empty()) return {};
    std::vector<double> n(g.size());
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            const double x = g.x(i), y = g.y(j);
            double value = rules.back().n;
            for (const ManningRule& r : rules)
                if ((!r.x_min || x >= *r.x_min) && (!r.x_max || x < *r.x_max) && (!r.y_min || y >= *r.y_min) &&
                    (!r.y_max || y < *r.y_max)) {
                    value = r.n;
                    break;
                }
            n[g.index(i, j)] = value;
        }
    return n;
}

}  // namespace flotsam
