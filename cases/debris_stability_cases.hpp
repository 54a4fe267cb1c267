// The debris stability cases, shared by the tests that pin the limits
// (tests/debris_stability_test.cpp) and by build/debris_stability, which prints the maps
// for the chart (docs/data/debris_stability.csv).
#pragma once
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "cases/debris_flows.hpp"
#include "debris/world.hpp"

namespace flotsam::test {

// ---- added mass: a body afloat at rest in a uniform 0.1 m/s current, 10 cm deep ----
constexpr double added_mass_current = 0.1;  // U [m/s]
inline const Grid added_mass_grid{400, 40, -0.995, -0.195, 0.01, 0.01};

inline std::string added_mass_flow(const std::string& dir) {
    return uniform_flow(dir + "/added_mass.nc", added_mass_grid, 20, 0.1, added_mass_current, 0.0);
}

// x velocity after each of `steps` steps of exactly `dt` (the vertex limit is lifted so
// that a growing oscillation keeps the step) [m/s].
inline std::vector<double> added_mass_velocities(const std::string& flow, double cm, debris::AddedMass treatment, int steps,
                                                 double dt = 0.01) {
    debris::WorldDef def = debris::default_world_def();
    def.step.dt_max = dt;
    def.step.vertex_step_fraction = 1e9;
    debris::World w(flow, {}, def);
    debris::BodyDef b = debris::default_body_def();
    b.x = -0.6;
    b.cm = cm;
    b.added_mass = treatment;
    w.add_body(b);
    std::vector<double> v;
    for (int k = 1; k <= steps; ++k) {
        w.advance_to(dt * k);
        v.push_back(w.states()[0].vx);
    }
    return v;
}

// Growth per step of the explicit scheme's step-to-step oscillation: o = v_explicit −
// v_implicit, δ_k = o_k − o_(k−1) ∝ (−C_a)^k (docs/debris.md), measured from step
// `from` to `to` as (|δ_to| / |δ_from|)^(1/(to − from)).
inline double explicit_growth_per_step(const std::vector<double>& v_explicit, const std::vector<double>& v_implicit, int from,
                                       int to) {
    auto delta = [&](int k) { return (v_explicit[k] - v_implicit[k]) - (v_explicit[k - 1] - v_implicit[k - 1]); };
    return std::pow(std::fabs(delta(to)) / std::fabs(delta(from)), 1.0 / (to - from));
}

// The analytic relaxation of the implicit scheme: v = U − U/(1 + t/τ),
// τ = M / (½ ρ (Cd1 + Cd2) B d U), M = m (1 + C_a) afloat [m/s].
inline double relaxation_velocity(double cm, double t) {
    const debris::BodyParams p = debris::make_body_params(debris::default_body_def(), 1000.0);
    const double M = p.mass * cm, U = added_mass_current;
    const double tau = M / (0.5 * 1000.0 * (p.def.cd1 + p.def.cd2) * p.def.width * p.draft * U);
    return U - U / (1.0 + t / tau);
}

// ---- tunnelling: a body carried at 3 m/s against a wall one cell thick ----
// The body reaches the far side when one step carries its centre past the wall's centre
// line from a position clear of it (the push-out then goes forward), that is when a step
// moves it more than about B/2 + Δx/2: 5.5 cells at 1 cm, 1.75 cells at 4 cm for the
// 10 cm wide box (across its width, its smallest extent).
inline Grid wall_grid(double cell) {  // 1.2 m square
    const int n = int(std::lround(1.2 / cell));
    return Grid{n, n, -0.6 + 0.5 * cell, -0.6 + 0.5 * cell, cell, cell};
}
// Centre line of the wall column: the column holding x = 0.305 m [m].
inline double wall_x(double cell) {
    const Grid g = wall_grid(cell);
    return g.x(g.cell_i(0.305));
}

inline std::string wall_flow(const std::string& dir, double cell) {
    return uniform_flow(dir + "/wall_" + std::to_string(int(std::lround(cell * 1000))) + "mm.nc", wall_grid(cell), 2, 0.1, 3.0,
                        0.0);
}

struct WallRun {
    double max_x = -1.0;  // furthest centre position [m]
    long steps = 0;
    bool tunnelled = false;  // the centre ended on the far side of the wall
};
// Starts at x = start_x, already at the current's speed; heading: long axis from +x
// [degree]; steps up to dt_max ≤ 0.1 s [s]; 0.4 s (1.2 m of travel if nothing stops it).
inline WallRun wall_run(const std::string& flow, double cell, double heading_deg, double vertex_step_fraction, double dt_max,
                        double start_x = 0.0) {
    debris::WorldDef def = debris::default_world_def();
    def.step.vertex_step_fraction = vertex_step_fraction;
    def.step.dt_max = dt_max;
    const Grid g = wall_grid(cell);
    std::vector<std::uint8_t> wall(g.size(), 0);
    for (int j = 0; j < g.ny; ++j) wall[g.index(g.cell_i(wall_x(cell)), j)] = 1;
    debris::World w(flow, wall, def);
    debris::BodyDef b = debris::default_body_def();
    b.x = start_x;
    b.heading = heading_deg * M_PI / 180.0;
    w.add_body(b);
    w.states()[0].vx = 3.0;
    WallRun r;
    for (int k = 1; k <= 4; ++k) {
        w.advance_to(0.1 * k);
        r.max_x = std::max(r.max_x, w.states()[0].x);
    }
    r.steps = w.stats()[0].steps;
    r.tunnelled = r.max_x > wall_x(cell);
    return r;
}

// Of `phases` runs started at evenly spaced points within one step's travel (the
// outcome depends on where the steps fall relative to the wall), how many went through.
inline int wall_tunnelling_count(const std::string& flow, double cell, double heading_deg, double vertex_step_fraction,
                                 int phases) {
    int n = 0;
    for (int p = 0; p < phases; ++p)
        n += wall_run(flow, cell, heading_deg, vertex_step_fraction, 0.1, -vertex_step_fraction * cell * p / phases).tunnelled ? 1
                                                                                                                               : 0;
    return n;
}

}  // namespace flotsam::test
