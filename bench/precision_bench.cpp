// Precision benchmark: the finite-volume scheme's row kernels, the same code
// (hydro/swe_rows.hpp, Heun's stage) compiled for float and for double, alone (the
// flows' state is float32 by default, `--precision`; docs/studies/hydro_speed_levers.md
// gives what it does to a whole run and its answers). Prints figures; asserts nothing.
//
//   precision_bench [--dem PATH] [--resolution 0.01] [--steps 20] [--rounds 3]
//
// The grid is the real layout (or the generated scene without the DEM) at the flows'
// finest spacing, flooded everywhere ("all wet": still water 1 cm above the highest roof,
// so no cell is skipped) with a smooth current on it (u = 0.3 + 0.2 sin(2 pi x / 0.5 m),
// v = 0.2 cos(2 pi y / 0.3 m) m/s), so that the limiters, fluxes and friction work on
// changing values. Each round advances it --steps forward-Euler stages of the second-order
// scheme (primitives, slopes and face fluxes in y and x, rates, update with implicit
// friction, the CFL rate), fused row by row as Solver::stage does, on one thread, first in
// double, then in float, from the same start; the best round of each is printed as
// cell-updates per processor second. The fronts, the dry-land skipping and the boundary
// forcing are left out: they are the same work in either precision.
//
// What the ratio means for a whole run: the row kernels were 67 % of a 1 cm flow's
// processor time with Heun steps (perf; docs/studies/hydro_speed_levers.md), so the
// line "whole 1 cm run at most" is 1 / (0.33 + 0.67 / ratio): Amdahl's bound, with
// nothing else made faster. The last line compares the two final states.
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "cases/bench_scene.hpp"
#include "hydro/swe_rows.hpp"

using namespace flotsam;
using namespace flotsam::hydro::rows;
using flotsam::hydro::kGhost;

namespace {

constexpr double kKernelShare = 0.67;  // the row kernels' share of a 1 cm Heun run's processor time (perf)

double processor_seconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// A padded grid (kGhost cells around; x fastest) in one precision.
template <class Real>
struct State {
    int nx = 0, ny = 0;
    std::size_t stride = 0;
    std::vector<Real> h, hu, hv, z, g_n2;
    Real* row(std::vector<Real>& a, int j) { return a.data() + std::size_t(j + kGhost) * stride; }
};

// The flooded start: still water above every roof, a smooth current.
template <class Real>
State<Real> flooded(const Scene& scene, const hydro::PhysicsDef& physics) {
    State<Real> s;
    s.nx = scene.grid.nx;
    s.ny = scene.grid.ny;
    s.stride = std::size_t(s.nx + 2 * kGhost);
    const std::size_t n = s.stride * std::size_t(s.ny + 2 * kGhost);
    for (auto* a : {&s.h, &s.hu, &s.hv, &s.z, &s.g_n2}) a->assign(n, Real(0));
    const double level = *std::max_element(scene.z.begin(), scene.z.end()) + 0.01;
    const double pi = std::numbers::pi;
    for (int j = -kGhost; j < s.ny + kGhost; ++j)
        for (int i = -kGhost; i < s.nx + kGhost; ++i) {
            const int ic = std::clamp(i, 0, s.nx - 1), jc = std::clamp(j, 0, s.ny - 1);  // ghosts copy the edge
            const std::size_t k = scene.grid.index(ic, jc);
            const double x = scene.grid.x(ic), y = scene.grid.y(jc);
            const double depth = level - scene.z[k];
            const double manning = scene.manning_n.empty() ? physics.default_manning_n : scene.manning_n[k];
            const std::size_t p = std::size_t(j + kGhost) * s.stride + std::size_t(i + kGhost);
            s.h[p] = Real(depth);
            s.hu[p] = Real(depth * (0.3 + 0.2 * std::sin(2.0 * pi * x / 0.5)));
            s.hv[p] = Real(depth * 0.2 * std::cos(2.0 * pi * y / 0.3));
            s.z[p] = Real(scene.z[k]);
            s.g_n2[p] = Real(physics.gravity * manning * manning);
        }
    return s;
}

struct Timing {
    double seconds = 0.0;  // processor time of the stages
    long cell_updates = 0;
};

// `steps` forward-Euler stages at cfl 0.4 (a stable step for Euler with these slopes),
// the ghosts held at their start; the result replaces s's state.
template <class Real>
Timing advance(State<Real>& s, const hydro::PhysicsDef& physics, const hydro::FiniteVolumeDef& fv, double dx, double dy,
               int steps) {
    const Sweep<Real> sw{
        Real(physics.gravity), Real(physics.dry_depth), Real(fv.limiter_theta), Real(1), Real(1.0 / dx), Real(1.0 / dy), s.nx};
    std::vector<Real> mem(RowBuffers<Real>::kRows * s.stride, Real(0));
    const RowBuffers<Real> w(mem.data(), s.stride);
    std::vector<Real> h_out = s.h, hu_out = s.hu, hv_out = s.hv;
    const hydro::ColumnRange cells{0, s.nx}, padded{-kGhost, s.nx + kGhost};
    Real rate = 0;
    for (int j = 0; j < s.ny; ++j)
        rate = std::max(rate, max_wave_rate_row(sw, cells, s.row(s.h, j), s.row(s.hu, j), s.row(s.hv, j)));
    auto primitives = [&](int j) {
        primitives_row(sw, padded, s.row(s.h, j), s.row(s.hu, j), s.row(s.hv, j), s.row(s.z, j), w.prim(j + kGhost, 0),
                       w.prim(j + kGhost, 1), w.prim(j + kGhost, 2));
    };
    auto slopes = [&](int j) { y_slopes_row(sw, cells, s.row(s.h, j - 1), s.row(s.h, j), s.row(s.h, j + 1), w, j + kGhost); };
    auto faces = [&](int j) { y_faces_row(sw, cells, s.row(s.h, j - 1), s.row(s.h, j), w, j + kGhost); };
    Timing t;
    const double start = processor_seconds();
    for (int step = 0; step < steps; ++step) {
        const Real dt = Real(0.4) / rate;
        long fixes = 0;
        Real worst = 0, next_rate = 0;
        for (int j = -kGhost; j < 2; ++j) primitives(j);
        for (int j = -1; j < 1; ++j) slopes(j);
        faces(0);
        for (int j = 0; j < s.ny; ++j) {
            primitives(j + 2);
            slopes(j + 1);
            faces(j + 1);
            rates_row(sw, cells, s.row(s.h, j), w, j + kGhost, nullptr);
            Real* ho = h_out.data() + std::size_t(j + kGhost) * s.stride;
            Real* huo = hu_out.data() + std::size_t(j + kGhost) * s.stride;
            Real* hvo = hv_out.data() + std::size_t(j + kGhost) * s.stride;
            update_row<Real, false, hydro::Friction::implicit>(sw, cells, dt, Real(0), s.row(s.h, j), s.row(s.hu, j),
                                                               s.row(s.hv, j), w, s.row(s.g_n2, j), nullptr, nullptr, nullptr, ho,
                                                               huo, hvo, fixes, worst);
            next_rate = std::max(next_rate, max_wave_rate_row(sw, cells, ho, huo, hvo));
        }
        std::swap(s.h, h_out);
        std::swap(s.hu, hu_out);
        std::swap(s.hv, hv_out);
        rate = next_rate;
        t.cell_updates += long(s.nx) * s.ny;
    }
    t.seconds = processor_seconds() - start;
    return t;
}

}  // namespace

int main(int argc, char** argv) {
    std::string dem = std::string(FLOTSAM_SHARED_DEFAULT) + "/data/city-topography-from-figure.nc";
    double resolution = 0.01;
    int steps = 20, rounds = 3;
    for (int k = 1; k < argc; k += 2) {
        const std::string option = argv[k];
        if (k + 1 == argc) {
            std::fprintf(stderr, "precision_bench: %s needs a value\n", option.c_str());
            return 2;
        }
        const char* value = argv[k + 1];
        if (option == "--dem") {
            dem = value;
        } else if (option == "--resolution") {
            resolution = std::atof(value);
        } else if (option == "--steps") {
            steps = std::max(1, std::atoi(value));
        } else if (option == "--rounds") {
            rounds = std::max(1, std::atoi(value));
        } else {
            std::fprintf(stderr, "precision_bench: unknown option %s\n", option.c_str());
            return 2;
        }
    }
    auto [scene, what] = test::bench_scene(dem, resolution);
    const hydro::PhysicsDef physics = hydro::default_physics_def();
    const hydro::FiniteVolumeDef fv;
    std::printf("precision_bench: %s at %.3g m, %d x %d cells, all wet, %d forward-Euler stages a round, best of %d, 1 thread\n",
                what.c_str(), resolution, scene.grid.nx, scene.grid.ny, steps, rounds);
    Timing best_double, best_float;
    State<double> end_double;
    State<float> end_float;
    for (int r = 0; r < rounds; ++r) {
        State<double> d = flooded<double>(scene, physics);
        const Timing td = advance(d, physics, fv, scene.grid.dx, scene.grid.dy, steps);
        State<float> f = flooded<float>(scene, physics);
        const Timing tf = advance(f, physics, fv, scene.grid.dx, scene.grid.dy, steps);
        if (r == 0 || td.seconds < best_double.seconds) best_double = td;
        if (r == 0 || tf.seconds < best_float.seconds) best_float = tf;
        std::printf("  round %d: double %.2f s, float %.2f s processor\n", r + 1, td.seconds, tf.seconds);
        end_double = std::move(d);
        end_float = std::move(f);
    }
    const double rate_double = double(best_double.cell_updates) / best_double.seconds;
    const double rate_float = double(best_float.cell_updates) / best_float.seconds;
    const double ratio = rate_float / rate_double;
    std::printf("  double: %.3g cell-stages per processor second (state %zu bytes a cell)\n", rate_double, 5 * sizeof(double));
    std::printf("  float:  %.3g cell-stages per processor second (state %zu bytes a cell)\n", rate_float, 5 * sizeof(float));
    std::printf("  float / double: %.2fx; whole 1 cm run at most %.2fx (kernels %.0f %% of it)\n", ratio,
                1.0 / (1.0 - kKernelShare + kKernelShare / ratio), 100.0 * kKernelShare);
    double worst = 0.0, sum2 = 0.0;
    long n = 0;
    for (int j = 0; j < end_double.ny; ++j)
        for (int i = 0; i < end_double.nx; ++i) {
            const std::size_t p = std::size_t(j + kGhost) * end_double.stride + std::size_t(i + kGhost);
            const double e = double(end_float.h[p]) - end_double.h[p];
            worst = std::max(worst, std::abs(e));
            sum2 += e * e;
            ++n;
        }
    std::printf("  depth after %d stages, float against double: %.3g m at most, %.3g m RMS\n", steps, worst,
                std::sqrt(sum2 / double(n)));
    return 0;
}
