// Synthetic flows for the debris tests, written with the stage-one FlowWriter, and the
// paper's body put down at a place.
#pragma once
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "common/atomic_file.hpp"
#include "common/grid.hpp"
#include "debris/body.hpp"
#include "formats/flow_file.hpp"

namespace flotsam::test {

struct FlowState {
    float h = 0, u = 0, v = 0;  // [m], [m/s], [m/s]
};
using BedFn = std::function<double(double x, double y)>;
using FieldFn = std::function<FlowState(double x, double y, double t)>;

inline std::string write_flow(const std::string& path, const Grid& g, const std::vector<double>& times, const BedFn& bed,
                              const FieldFn& field, const std::map<std::string, std::string>& attributes = {},
                              int chunk = FlowFileDef{}.chunk, int deflate_level = FlowFileDef{}.deflate_level) {
    FlowFileDef def;
    def.attributes = attributes;
    def.chunk = chunk;
    def.deflate_level = deflate_level;
    def.window = g;
    def.frame_times = times;
    def.z.resize(g.size());
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) def.z[g.index(i, j)] = float(bed(g.x(i), g.y(j)));
    {
        FlowWriter w(path, def);
        std::vector<float> h(g.size()), u(g.size()), v(g.size());
        for (std::size_t k = 0; k < times.size(); ++k) {
            for (int j = 0; j < g.ny; ++j)
                for (int i = 0; i < g.nx; ++i) {
                    const FlowState s = field(g.x(i), g.y(j), times[k]);
                    h[g.index(i, j)] = s.h;
                    u[g.index(i, j)] = s.u;
                    v[g.index(i, j)] = s.v;
                }
            w.write_frame(k, h, u, v);
        }
        std::vector<float> zero(g.size(), 0.0f);
        w.write_summary(zero, zero, zero);
        w.close();
    }
    return path;
}

// The paper's body (debris::default_body_def) centred at (x, y) [m] with `heading` [rad].
inline debris::BodyDef body_at(double x, double y, double heading, debris::ContactModel contact = debris::ContactModel::local) {
    debris::BodyDef b = debris::default_body_def();
    b.x = x;
    b.y = y;
    b.heading = heading;
    b.contact = contact;
    return b;
}

// A steady flow of uniform depth and velocity over a flat bed, frames every second.
inline std::string uniform_flow(const std::string& path, const Grid& g, double t_end, double depth, double u, double v,
                                double bed = -0.1) {
    std::vector<double> times;
    for (double t = 0; t <= t_end + 1e-9; t += 1.0) times.push_back(t);
    return write_flow(
        path, g, times, [=](double, double) { return bed; },
        [=](double, double, double) {
            return FlowState{float(depth), float(u), float(v)};
        });
}

}  // namespace flotsam::test
