// Test cases shared by the hydro tests of both schemes: scenes, closed boundaries, and
// the exact dam breaks (Stoker on a wet bed, Ritter on a dry one).
#pragma once
#include <algorithm>
#include <cmath>
#include <random>

#include "common/scene.hpp"
#include "hydro/solver.hpp"

namespace flotsam::test {

inline Scene flat_scene(int nx, int ny, double dx, double x0, double bed) {
    Scene s;
    s.grid = Grid{nx, ny, x0 + 0.5 * dx, 0.5 * dx, dx, dx};
    s.z.assign(s.grid.size(), bed);
    return s;
}

// Walls on all sides, no friction.
inline hydro::SolverDef closed_def() {
    hydro::SolverDef d;
    d.west.kind = d.east.kind = d.south.kind = d.north.kind = hydro::BoundaryKind::wall;
    d.default_manning_n = 0.0;
    return d;
}

// A bumpy basin with 5 cm "buildings" standing out of still water at level 0.
inline Scene city_basin(int nx, int ny, unsigned seed) {
    Scene s = flat_scene(nx, ny, 0.01, 0.0, 0.0);
    std::mt19937 rng(seed);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            double z = -0.03 + 0.02 * std::sin(0.3 * i) * std::cos(0.2 * j) + 0.004 * double(rng() % 1000) / 1000.0;
            if ((i / 6) % 3 == 1 && (j / 5) % 3 == 1) z = 0.05;  // building blocks
            if (i > nx - 8) z = 0.01 + 0.001 * (i - nx + 8);     // dry shore
            s.z[s.grid.index(i, j)] = z;
        }
    return s;
}

// city_basin(80, 50, seed) with a column of water 8 cm above still water over its
// first 20 columns: released, it floods the city's streets around the buildings.
inline Scene flooded_basin(unsigned seed) {
    Scene s = city_basin(80, 50, seed);
    s.eta0.assign(s.grid.size(), 0.0);
    for (int j = 0; j < s.grid.ny; ++j)
        for (int i = 0; i < 20; ++i) s.eta0[s.grid.index(i, j)] = 0.08;
    return s;
}

// How far a lake at rest has moved: the largest |level| of a wet cell [m], the largest
// speed [m/s], and the deepest water on ground above still water (the roofs) [m].
struct RestDrift {
    double level = 0.0, speed = 0.0, roof_depth = 0.0;
};
template <class S>
RestDrift rest_drift(const S& solver, const Scene& s) {
    RestDrift r;
    for (int j = 0; j < s.grid.ny; ++j)
        for (int i = 0; i < s.grid.nx; ++i) {
            if (solver.depth(i, j) > 0.0) r.level = std::max(r.level, std::abs(solver.level(i, j)));
            r.speed = std::max(r.speed, std::hypot(solver.x_velocity(i, j), solver.y_velocity(i, j)));
            if (s.z[s.grid.index(i, j)] > 0.0) r.roof_depth = std::max(r.roof_depth, solver.depth(i, j));
        }
    return r;
}

// Smallest depth of any cell [m].
template <class S>
double min_depth(const S& solver) {
    double m = 0.0;
    for (int j = 0; j < solver.grid().ny; ++j)
        for (int i = 0; i < solver.grid().nx; ++i) m = std::min(m, solver.depth(i, j));
    return m;
}

// Stoker's dam break (wet bed, hr > 0) or Ritter's (dry bed) at x/t = xi.
inline double dam_break_depth(double hl, double hr, double g, double xi) {
    const double cl = std::sqrt(g * hl);
    if (xi <= -cl) return hl;
    if (hr <= 0.0) return xi < 2.0 * cl ? (2.0 * cl - xi) * (2.0 * cl - xi) / (9.0 * g) : 0.0;
    // Middle depth hm: rarefaction u_m = 2(cl - cm) equals the shock's u_m = S (1 - hr/hm).
    auto mismatch = [&](double hm) {
        const double S = std::sqrt(g * hm * (hm + hr) / (2.0 * hr));
        return 2.0 * (cl - std::sqrt(g * hm)) - S * (1.0 - hr / hm);
    };
    double lo = hr, hi = hl;
    for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi);
        (mismatch(mid) > 0.0 ? lo : hi) = mid;
    }
    const double hm = 0.5 * (lo + hi), cm = std::sqrt(g * hm);
    const double S = std::sqrt(g * hm * (hm + hr) / (2.0 * hr));
    const double um = 2.0 * (cl - cm);
    if (xi < um - cm) return (2.0 * cl - xi) * (2.0 * cl - xi) / (9.0 * g);
    if (xi < S) return hm;
    return hr;
}

// L1 error [m^2] of the depth against the exact dam break (hl | hr at x = 0) at t_end, on
// nx cells over [-5, 5], transmissive ends, no friction, dry tolerance 1e-8 m. `make`
// builds the solver from (scene, def); `tune` may change the def first.
template <class Make, class Tune>
double dam_break_error(int nx, double hl, double hr, double t_end, Make&& make, Tune&& tune) {
    Scene s = flat_scene(nx, 2, 10.0 / nx, -5.0, 0.0);
    s.eta0.assign(s.grid.size(), 0.0);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < nx; ++i) s.eta0[s.grid.index(i, j)] = s.grid.x(i) < 0.0 ? hl : hr;
    hydro::SolverDef d = closed_def();
    d.west.kind = d.east.kind = hydro::BoundaryKind::transmissive;
    d.dry_depth = 1e-8;
    tune(d);
    auto solver = make(s, d);
    while (solver.time() < t_end - 1e-12) solver.step(std::min(solver.stable_dt(), t_end - solver.time()));
    double err = 0.0;
    for (int i = 0; i < nx; ++i)
        err += std::abs(solver.depth(i, 0) - dam_break_depth(hl, hr, d.gravity, s.grid.x(i) / t_end)) * s.grid.dx;
    return err;
}

}  // namespace flotsam::test
