// Hydro cases shared by the tests of both schemes and by the stability map
// (bench/hydro_stability.cpp): scenes, closed boundaries, the exact dam breaks (Stoker
// on a wet bed, Ritter on a dry one), and a runner that watches a run for failure.
#pragma once
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "formats/scene.hpp"
#include "hydro/solver.hpp"

namespace flotsam::test {

inline Scene flat_scene(int nx, int ny, double dx, double x0, double bed) {
    Scene s;
    s.grid = Grid{nx, ny, x0 + 0.5 * dx, 0.5 * dx, dx, dx};
    s.z.assign(s.grid.size(), bed);
    return s;
}

// Walls on all sides, no friction.
inline hydro::PhysicsDef closed_def() {
    hydro::PhysicsDef d;
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

// The dam break hl | hr [m] at x = 0 on nx x 2 cells over [-5, 5] m, flat bed at 0.
inline Scene dam_break_scene(int nx, double hl, double hr) {
    Scene s = flat_scene(nx, 2, 10.0 / nx, -5.0, 0.0);
    s.eta0.assign(s.grid.size(), 0.0);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < nx; ++i) s.eta0[s.grid.index(i, j)] = s.grid.x(i) < 0.0 ? hl : hr;
    return s;
}

// L1 error [m^2] of the depth against the exact dam break (hl | hr at x = 0) at t_end, on
// nx cells over [-5, 5], transmissive ends, no friction, dry tolerance 1e-8 m. `make`
// builds the solver from (scene, def); `tune` may change the def first.
template <class Make, class Tune>
double dam_break_error(int nx, double hl, double hr, double t_end, Make&& make, Tune&& tune) {
    const Scene s = dam_break_scene(nx, hl, hr);
    hydro::PhysicsDef d = closed_def();
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

// Ritter's dam break in a box: [0, 10] m, h0 [m] of still water west of the
// dam at x = 5 m, dry flat ground east of it, nx x 4 cells, walls, no friction. At
// t0 > 0 the scene holds the exact solution at that time instead (depth and velocity:
// a resolved fan, for the transport of the front alone). The exact wet tip is at
// x = 5 + 2 sqrt(g h0) t until it reaches the east wall.
inline Scene ritter_box(int nx, double h0, double t0 = 0.0, double g = 9.81) {
    Scene s = flat_scene(nx, 4, 10.0 / nx, 0.0, 0.0);
    s.eta0.assign(s.grid.size(), 0.0);
    if (t0 > 0.0) s.u0.assign(s.grid.size(), 0.0), s.v0.assign(s.grid.size(), 0.0);
    const double c0 = std::sqrt(g * h0);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < nx; ++i) {
            const std::size_t k = s.grid.index(i, j);
            if (t0 <= 0.0) {
                s.eta0[k] = s.grid.x(i) < 5.0 ? h0 : 0.0;
                continue;
            }
            const double xi = (s.grid.x(i) - 5.0) / t0;
            s.eta0[k] = dam_break_depth(h0, 0.0, g, xi);
            s.u0[k] = s.eta0[k] > 0.0 && xi > -c0 ? 2.0 / 3.0 * (xi + c0) : 0.0;  // in the fan
        }
    return s;
}

// What a run of ritter_box gives at t_end: the wet front (the east edge of the last
// cell with h > front_depth) [m], the exact tip and the exact position of front_depth
// [m], the L1 error of the depth against Ritter's solution [m^2], the smallest depth
// the solver saw before its round-off clamp [m] and the relative volume change.
struct RitterFront {
    double front = 0.0, tip = 0.0, exact_front = 0.0, l1 = 0.0, dx = 0.0, min_depth_seen = 0.0, volume_change = 0.0;
};

// ritter_box(nx, h0, t0) run from t0 to t_end by the solver that `make(scene, def)`
// builds, with closed_def() (walls, no friction, every other setting at its default).
template <class Make>
RitterFront ritter_front(int nx, double h0, double t0, double t_end, double front_depth, Make&& make) {
    const Scene s = ritter_box(nx, h0, t0);
    const hydro::PhysicsDef d = closed_def();
    auto solver = make(s, d);
    solver.set_time(t0);
    const double v0 = solver.volume();
    while (solver.time() < t_end - 1e-12) solver.step(std::min(solver.stable_dt(), t_end - solver.time()));
    RitterFront r;
    r.dx = s.grid.dx;
    r.tip = 5.0 + 2.0 * std::sqrt(d.gravity * h0) * t_end;
    r.exact_front = r.tip - t_end * std::sqrt(9.0 * d.gravity * front_depth);  // h = (2 c0 - xi)^2 / (9 g)
    for (int i = 0; i < nx; ++i) {
        const double h = solver.depth(i, 0);
        if (h > front_depth) r.front = s.grid.x(i) + 0.5 * s.grid.dx;
        r.l1 += std::abs(h - dam_break_depth(h0, 0.0, d.gravity, (s.grid.x(i) - 5.0) / t_end)) * s.grid.dx;
    }
    r.min_depth_seen = solver.stats().min_depth_seen;
    r.volume_change = solver.volume() / v0 - 1.0;
    return r;
}

// Thacker's planar surface in a paraboloid (Thacker 1981, J. Fluid Mech. 107:499): bed
// z = -h0 (1 - r^2 / a^2), a tilted plane of water sloshing around the bowl without
// friction, u = -eta omega sin(omega t), v = eta omega cos(omega t), omega =
// sqrt(2 g h0) / a, level eta h0 / a^2 (2 x cos(omega t) + 2 y sin(omega t) - eta).
// n x n cells over [-2, 2]^2, a = 1 m, h0 = 0.1 m, eta = 0.5 m: at t = 0 every wet cell
// moves north at 0.70 m/s (the scene's u0, v0), a scene that starts moving.
struct Thacker {
    double a = 1.0, h0 = 0.1, eta = 0.5, g = 9.81;
    double omega() const { return std::sqrt(2.0 * g * h0) / a; }
    double bed(double x, double y) const { return -h0 * (1.0 - (x * x + y * y) / (a * a)); }
    double level(double x, double y, double t) const {
        return eta * h0 / (a * a) * (2.0 * x * std::cos(omega() * t) + 2.0 * y * std::sin(omega() * t) - eta);
    }
    double period() const { return 2.0 * std::acos(-1.0) / omega(); }  // [s]
    // level - bed = h0 (1 - |(x, y) - c(t)|^2 / a^2), c(t) = eta (cos, sin)(omega t): a disc
    // of water of radius a whose centre circles the bowl's at distance eta; 0 outside it.
    double depth(double x, double y, double t) const { return std::max(0.0, level(x, y, t) - bed(x, y)); }
    double x_velocity(double t) const { return -eta * omega() * std::sin(omega() * t); }  // where wet [m/s]
    double y_velocity(double t) const { return eta * omega() * std::cos(omega() * t); }
};
inline Scene thacker_planar(int n, const Thacker& th = Thacker{}) {
    Scene s = flat_scene(n, n, 4.0 / n, -2.0, 0.0);
    s.grid.y0 = -2.0 + 0.5 * s.grid.dy;
    s.eta0.assign(s.grid.size(), 0.0);
    s.u0.assign(s.grid.size(), 0.0);
    s.v0.assign(s.grid.size(), 0.0);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const std::size_t k = s.grid.index(i, j);
            const double x = s.grid.x(i), y = s.grid.y(j);
            s.z[k] = th.bed(x, y);
            s.eta0[k] = std::max(th.level(x, y, 0.0), s.z[k]);
            if (s.eta0[k] > s.z[k]) s.v0[k] = th.eta * th.omega();
        }
    return s;
}

// A square basin of n x n cells of 2.5 cm, 0.5 m deep, with a Gaussian hump of 1 cm
// (width 0.1 m) at its centre: a linear wave for the Courant limit.
inline Scene basin_wave(int n) {
    Scene s = flat_scene(n, n, 0.025, 0.0, -0.5);
    s.eta0.assign(s.grid.size(), 0.0);
    const double c = 0.5 * n * 0.025;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            s.eta0[s.grid.index(i, j)] = 0.01 * std::exp(-(std::pow(s.grid.x(i) - c, 2) + std::pow(s.grid.y(j) - c, 2)) / 0.01);
    return s;
}

// A bore into a block of buildings: 1.2 m x 0.4 m of 1 cm cells, a street at z = 0
// under a 1 mm film of still water, nine buildings 4 and 5 cm high (8 x 8 cells, 4-cell
// streets between them) from x = 0.5 m, and a 3 cm column of water west of x = 0.3 m.
inline Scene bore_into_buildings() {
    Scene s = flat_scene(120, 40, 0.01, 0.0, 0.0);
    s.eta0.assign(s.grid.size(), 0.001);
    s.building.assign(s.grid.size(), 0);
    for (int j = 0; j < s.grid.ny; ++j)
        for (int i = 0; i < s.grid.nx; ++i) {
            const std::size_t k = s.grid.index(i, j);
            const int bi = i - 50, bj = j - 2;  // the block's corner cell
            if (bi >= 0 && bi < 32 && bj >= 0 && bj < 32 && bi % 12 < 8 && bj % 12 < 8) {
                s.z[k] = (bi / 12 + bj / 12) % 2 == 0 ? 0.05 : 0.04;
                s.building[k] = 1;
            }
            if (s.grid.x(i) < 0.3) s.eta0[k] = 0.03;
        }
    return s;
}

// A thin film on a 1:10 slope: 100 x 4 cells of 1 cm, depth 0.1 mm everywhere, Manning
// n = 0.025 (set it in the def). Explicit friction on it has dt g n^2 |u| / h^(4/3) >> 1.
inline Scene film_on_slope() {
    Scene s = flat_scene(100, 4, 0.01, 0.0, 0.0);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 100; ++i) s.z[s.grid.index(i, j)] = -0.1 * s.grid.x(i);
    s.eta0.assign(s.grid.size(), 0.0);
    for (std::size_t k = 0; k < s.z.size(); ++k) s.eta0[k] = s.z[k] + 1e-4;
    return s;
}

// What happened in a run watched step by step (run_watched).
struct Watch {
    bool finite = true;         // every depth and velocity stayed finite
    double level_rise = 0.0;    // largest level above the highest initial level [m]
    double max_speed = 0.0;     // [m/s]
    double min_depth = 0.0;     // smallest depth after any step [m]
    double roof_depth = 0.0;    // deepest water on a cell marked as building [m]
    long reversals = 0;         // cell-steps where a wet cell's x-velocity changed sign
    double volume_error = 0.0;  // relative, end against start
    long steps = 0;
    double first_step = 0.0;    // [s]
    double level_bound = 0.01;  // [m] a level this far above the highest initial one is growth, not flow
    bool blew_up() const { return !finite || level_rise > level_bound || max_speed > 50.0; }
};

// Steps `solver` to t_end with its own stable step, watching every cell after every
// step; stops early once the run has blown up: non-finite values, a speed above 50 m/s,
// or a level more than `level_bound` [m] above the highest initial level (none of the
// cases can raise the water above where it started).
template <class S>
Watch run_watched(S& solver, const Scene& s, double t_end, double level_bound = 0.01) {
    Watch w;
    w.level_bound = level_bound;
    const Grid& g = solver.grid();
    double level0 = -1e300;
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i)
            if (solver.depth(i, j) > 0.0) level0 = std::max(level0, solver.level(i, j));
    const double v0 = solver.volume();
    std::vector<double> u_prev(g.size(), 0.0);
    const double dry = solver.def().dry_depth;
    while (solver.time() < t_end - 1e-12 && !w.blew_up()) {
        const double dt = std::min(solver.stable_dt(), t_end - solver.time());
        if (w.steps == 0) w.first_step = dt;
        solver.step(dt);
        ++w.steps;
        for (int j = 0; j < g.ny; ++j)
            for (int i = 0; i < g.nx; ++i) {
                const double h = solver.depth(i, j), u = solver.x_velocity(i, j), v = solver.y_velocity(i, j);
                if (!std::isfinite(h) || !std::isfinite(u) || !std::isfinite(v)) {
                    w.finite = false;
                    continue;
                }
                w.min_depth = std::min(w.min_depth, h);
                if (h > dry) w.level_rise = std::max(w.level_rise, solver.level(i, j) - level0);
                w.max_speed = std::max(w.max_speed, std::hypot(u, v));
                if (!s.building.empty() && s.building[g.index(i, j)]) w.roof_depth = std::max(w.roof_depth, h);
                double& up = u_prev[g.index(i, j)];
                if (h > dry && u * up < 0.0) ++w.reversals;
                up = u;
            }
    }
    w.volume_error = solver.volume() / v0 - 1.0;
    return w;
}

}  // namespace flotsam::test
