// How close the flows come to this machine's limit. Prints figures; asserts nothing.
//
//   hydro_limit [--dem PATH] [--seconds-2cm 60] [--seconds-1cm 20] [--scratch DIR]
//
// 1. The solver: the default scheme (split steps, float32 state) on the real layout with
//    the benchmark's pump forcing on the scene's recommended grids (nested 4:1 west of
//    x = -1.2 m), one thread, at 2 cm and 1 cm: cell-updates per processor second, all
//    cells and those computed (dry land is skipped).
// 2. The work per cell-update, counted from the kernels: the split step's row kernels
//    (hydro/split_rows.hpp) run once over a flooded grid in a number type that counts
//    each operation (Counted below), an x sweep and a y sweep with the step's friction
//    and CFL rate; and the bytes a cell's state moves per step (each sweep reads h, hu,
//    hv, the bed and the friction coefficient and writes h, hu, hv), besides the row
//    buffers, which stay in the core's caches.
// 3. The machine: a STREAM-like triad (a = b + s c) over arrays of the flows' state size
//    and far larger than the caches, one thread; and the throughput of each operation in
//    512-bit float vectors (add and multiply, min and max, compare and select, divide,
//    square root) on arrays in the first-level cache.
// 4. The limit: a cell-update can take no less than the longer of its bytes at the
//    triad's rate and its operations at their throughputs (divisions and roots share the
//    divider; the others the vector ports); the fraction printed is that time over the
//    measured one. Processor times, so a busy machine inflates both sides alike for the
//    solver, less so for the short machine loops (best of several rounds).
#include <omp.h>
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "cases/bench_scene.hpp"
#include "hydro/run.hpp"

namespace counting {

// Operations counted per class.
struct Ops {
    double add = 0, mul = 0, div = 0, sqrt = 0, minmax = 0, compare = 0;
};
inline Ops ops;

// A float that counts what is done with it (the kernels are templates on their number type).
struct Counted {
    float v = 0;
    Counted() = default;
    Counted(double x) : v(float(x)) {}
    explicit operator float() const { return v; }
};
inline Counted operator+(Counted a, Counted b) { return ++ops.add, Counted(a.v + b.v); }
inline Counted operator-(Counted a, Counted b) { return ++ops.add, Counted(a.v - b.v); }
inline Counted operator-(Counted a) { return ++ops.add, Counted(-a.v); }
inline Counted operator*(Counted a, Counted b) { return ++ops.mul, Counted(a.v * b.v); }
inline Counted operator/(Counted a, Counted b) { return ++ops.div, Counted(a.v / b.v); }
inline Counted& operator+=(Counted& a, Counted b) { return a = a + b; }
inline Counted& operator-=(Counted& a, Counted b) { return a = a - b; }
inline Counted& operator*=(Counted& a, Counted b) { return a = a * b; }
inline bool operator<(Counted a, Counted b) { return ++ops.compare, a.v < b.v; }
inline bool operator>(Counted a, Counted b) { return ++ops.compare, a.v > b.v; }
inline bool operator<=(Counted a, Counted b) { return ++ops.compare, a.v <= b.v; }
inline bool operator>=(Counted a, Counted b) { return ++ops.compare, a.v >= b.v; }
inline bool operator==(Counted a, Counted b) { return ++ops.compare, a.v == b.v; }
inline bool operator!=(Counted a, Counted b) { return ++ops.compare, a.v != b.v; }
inline Counted sqrt(Counted a) { return ++ops.sqrt, Counted(std::sqrt(a.v)); }
inline Counted abs(Counted a) { return ++ops.minmax, Counted(std::abs(a.v)); }
inline Counted min(Counted a, Counted b) { return ++ops.minmax, Counted(std::min(a.v, b.v)); }
inline Counted max(Counted a, Counted b) { return ++ops.minmax, Counted(std::max(a.v, b.v)); }
#pragma omp declare reduction(min : Counted : omp_out = omp_in.v < omp_out.v ? omp_in : omp_out) initializer(omp_priv = omp_orig)
#pragma omp declare reduction(max : Counted : omp_out = omp_in.v > omp_out.v ? omp_in : omp_out) initializer(omp_priv = omp_orig)

}  // namespace counting

#include "hydro/split_rows.hpp"

using namespace flotsam;
using counting::Counted;
using flotsam::hydro::kGhost;

namespace {

double processor_seconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// ---- 1. the solver ----

struct Flow {
    double cpu = 0.0, updates = 0.0, computed = 0.0, cells_fine = 0.0;  // [s], cell-updates, of which computed
};

Flow run_flow(const std::string& dem, double resolution, double seconds, const std::string& scratch) {
    auto [scene, what] = test::bench_scene(dem, resolution);
    const std::string path = scratch + "/scene-" + std::to_string(resolution) + ".nc";
    write_scene(path, scene, "hydro_limit");
    hydro::PhysicsDef physics = hydro::default_physics_def();
    physics.west.kind = hydro::BoundaryKind::pump;
    hydro::RunDef run;
    run.scene_file = path;
    run.out_file = scratch + "/flow-" + std::to_string(resolution) + ".nc";
    std::filesystem::remove(run.out_file);
    run.duration = seconds;
    run.output_interval = 1.0;
    run.window = std::array<double, 4>{-1.0, 8.1, -4.1, 0.0};
    run.nest = hydro::NestDef{-1.2, 4};
    run.quiet = true;
    omp_set_num_threads(1);
    const hydro::RunResult r = hydro::run_hydro(run, physics);
    Flow f;
    f.cpu = r.cpu_seconds;
    f.updates = r.cell_updates_per_second * r.wall_seconds;
    f.computed = f.updates * (1.0 - r.dry_skipped_fraction);
    return f;
}

// ---- 2. the work per cell-update ----

struct Work {
    counting::Ops ops;       // per cell-update
    double state_bytes = 0;  // [B] per cell-update, to and from wherever the state lives
};

// One split step (an x sweep, then the y sweep with friction and the CFL rate) over a
// flooded nx x ny grid in counted numbers; the operations per cell.
Work count_work(int nx, int ny) {
    using namespace flotsam::hydro::split;
    const std::size_t stride = std::size_t(nx + 2 * kGhost), n = stride * std::size_t(ny + 2 * kGhost);
    std::vector<Counted> h(n), hu(n), hv(n), z(n), g_n2(n), h1(n), hu1(n), hv1(n), h2(n), hu2(n), hv2(n);
    for (std::size_t p = 0; p < n; ++p) {
        const double x = double(p % stride), y = double(p / stride);
        z[p] = -0.3 + 0.01 * std::sin(x / 7.0) * std::cos(y / 5.0);
        h[p] = 0.3 - z[p].v + 0.002 * std::sin(x / 3.0 + y / 4.0);
        hu[p] = h[p].v * (0.3 + 0.1 * std::sin(x / 9.0));
        hv[p] = h[p].v * 0.2 * std::cos(y / 6.0);
        g_n2[p] = 9.81 * 0.013 * 0.013;
    }
    const Sweep<Counted> s{9.81, 1e-6, 1.3, 1.0, 1.0 / 0.02, 1.0 / 0.02, nx};
    std::vector<Counted> mem(Buffers<Counted>::kRows * stride);
    const Buffers<Counted> w(mem.data(), stride);
    auto row = [&](std::vector<Counted>& a, int j) { return a.data() + std::size_t(j + kGhost) * stride; };
    const Counted dt = 0.004, hdt_y = 0.5 * 0.004 / 0.02;
    long fixes = 0;
    Counted worst = 0, rate = 0;
    counting::ops = {};
    for (int j = 0; j < ny; ++j)  // the x sweep, now into 1
        x_row<Counted, false, false>(s, {0, nx}, dt, 0.0, row(h, j), row(hu, j), row(hv, j), row(z, j), row(g_n2, j), w, row(h1, j),
                                     row(hu1, j), row(hv1, j), fixes, worst, rate);
    for (int j = -kGhost; j < ny + kGhost; ++j)  // the ghosts of 1: copies of the edge rows
        if (j < 0 || j >= ny)
            for (auto* a : {&h1, &hu1, &hv1}) std::copy_n(row(*a, std::clamp(j, 0, ny - 1)), stride, row(*a, j));
    const int c0 = kGhost, c1 = nx + kGhost;
    for (int j = -2; j < 2; ++j) y_primitives_row(s, c0, c1, row(h1, j), row(hu1, j), row(hv1, j), row(z, j), w, j + kGhost);
    for (int j = -1; j < 1; ++j) y_slopes_row(s, c0, c1, hdt_y, row(h1, j - 1), row(h1, j), row(h1, j + 1), w, j + kGhost);
    y_faces_row(s, c0, c1, row(h1, -1), row(h1, 0), w, kGhost);
    for (int j = 0; j < ny; ++j) {  // the y sweep, 1 into 2, friction and the CFL rate
        if (j + 2 < ny + kGhost) y_primitives_row(s, c0, c1, row(h1, j + 2), row(hu1, j + 2), row(hv1, j + 2), row(z, j + 2), w, j + 2 + kGhost);
        y_slopes_row(s, c0, c1, hdt_y, row(h1, j), row(h1, j + 1), row(h1, std::min(j + 2, ny + 1)), w, j + 1 + kGhost);
        y_faces_row(s, c0, c1, row(h1, j), row(h1, j + 1), w, j + 1 + kGhost);
        y_update_row<Counted, true, true>(s, {0, nx}, dt, dt, row(h1, j), row(hu1, j), row(hv1, j), row(g_n2, j), w, j + kGhost,
                                          row(h2, j), row(hu2, j), row(hv2, j), fixes, worst, rate);
    }
    Work out;
    const double cells = double(nx) * double(ny);
    out.ops = counting::ops;
    for (double* v : {&out.ops.add, &out.ops.mul, &out.ops.div, &out.ops.sqrt, &out.ops.minmax, &out.ops.compare}) *v /= cells;
    out.state_bytes = 2.0 * (5.0 + 3.0) * sizeof(float);
    return out;
}

// ---- 3. the machine ----

// Best of `rounds` of f() [processor s].
template <class F>
double best_seconds(int rounds, F&& f) {
    double best = 1e300;
    for (int r = 0; r < rounds; ++r) {
        const double t0 = processor_seconds();
        f();
        best = std::min(best, processor_seconds() - t0);
    }
    return best;
}

// Triad a = b + s c over arrays of `n` floats [bytes/s], 12 bytes an element.
double triad_rate(std::size_t n) {
    std::vector<float> a(n, 0.0f), b(n, 1.0f), c(n, 2.0f);
    const int repeat = int(std::max<std::size_t>(1, (std::size_t(1) << 28) / n));
    const double t = best_seconds(5, [&] {
        for (int k = 0; k < repeat; ++k) {
            const float s = 0.5f + 1e-9f * float(k);
#pragma omp simd
            for (std::size_t i = 0; i < n; ++i) a[i] = b[i] + s * c[i];
            asm volatile("" : : "r"(a.data()) : "memory");
        }
    });
    return 12.0 * double(n) * repeat / t;
}

// Element-operations per second of op(v, x, y) applied 8 times in each of 4 independent
// chains per element (so that the processor can overlap them), 512-bit vectors of floats
// on arrays in the first-level cache.
template <class Op>
double op_rate(Op op) {
    constexpr std::size_t n = 1024;
    constexpr int repeat = 40000;
    std::vector<float> x(n), y(n), out(n);
    for (std::size_t i = 0; i < n; ++i) {
        x[i] = 1.0f + 1e-4f * float(i);
        y[i] = 0.5f + 1e-4f * float(i);
    }
    const double t = best_seconds(5, [&] {
        for (int k = 0; k < repeat; ++k) {
#pragma omp simd
            for (std::size_t i = 0; i < n; ++i) {
                float a = x[i], b = y[i], c = x[i] + y[i], d = x[i] - y[i];
                for (int q = 0; q < 8; ++q) {
                    a = op(a, x[i], y[i]);
                    b = op(b, x[i], y[i]);
                    c = op(c, x[i], y[i]);
                    d = op(d, x[i], y[i]);
                }
                out[i] = a + b + c + d;
            }
            asm volatile("" : : "r"(out.data()) : "memory");
        }
    });
    return 32.0 * double(n) * repeat / t;
}

}  // namespace

int main(int argc, char** argv) {
    std::string dem = std::string(FLOTSAM_SHARED_DEFAULT) + "/data/city-topography-from-figure.nc";
    double seconds_2cm = 60.0, seconds_1cm = 20.0;
    std::string scratch = (std::filesystem::temp_directory_path() / "flotsam-hydro-limit").string();
    for (int k = 1; k + 1 < argc; k += 2) {
        const std::string a = argv[k];
        if (a == "--dem")
            dem = argv[k + 1];
        else if (a == "--seconds-2cm")
            seconds_2cm = std::atof(argv[k + 1]);
        else if (a == "--seconds-1cm")
            seconds_1cm = std::atof(argv[k + 1]);
        else if (a == "--scratch")
            scratch = argv[k + 1];
    }
    std::filesystem::create_directories(scratch);

    // 2. the work, counted.
    const Work work = count_work(464, 24);
    const counting::Ops& o = work.ops;
    std::printf("hydro_limit: the default scheme's work per cell-update (split step, float32, counted from the kernels)\n");
    std::printf("  %.0f add/sub, %.0f mul, %.1f div, %.1f sqrt, %.0f min/max/abs, %.0f compare (each with a select); "
                "%.0f flops in all\n",
                o.add, o.mul, o.div, o.sqrt, o.minmax, o.compare, o.add + o.mul + o.div + o.sqrt);
    std::printf("  state: %.0f bytes read and written (h, hu, hv, bed, friction in; h, hu, hv out; each sweep)\n", work.state_bytes);

    // 3. the machine.
    // Each a pair of operations (a multiply and an add; a min and a max; a compare and its select).
    const double fp_ops = 2.0 * op_rate([](float v, float x, float y) { return v * x + y; });
    const double minmax = 2.0 * op_rate([](float v, float x, float y) { return std::max(std::min(v, x), y); });
    const double select = op_rate([](float v, float x, float y) { return v < x ? y : v; });
    const double div = op_rate([](float v, float x, float) { return x / v; });
    const double root = op_rate([](float v, float, float) { return std::sqrt(v); });
    std::printf("this machine, one core, 512-bit float vectors: %.3g add/mul, %.3g min/max, %.3g compare-and-select, %.3g div, "
                "%.3g sqrt per second\n",
                fp_ops, minmax, select, div, root);
    const double dram = triad_rate(std::size_t(48) << 20);  // 3 x 192 MB
    // The flows' state: 11 arrays (three states of h, hu, hv; bed, friction) of the fine grid.
    const double state_2cm = triad_rate(std::size_t(464 * 204 * 11 / 3));
    const double state_1cm = triad_rate(std::size_t(928 * 404 * 11 / 3));
    std::printf("  triad: %.3g B/s far beyond the caches, %.3g B/s at the 2 cm state's size, %.3g B/s at the 1 cm state's size\n",
                dram, state_2cm, state_1cm);
    // The divider does divisions and roots; the vector ports the rest (a compare with its select).
    const double t_divider = o.div / div + o.sqrt / root;
    const double t_ports = (o.add + o.mul) / fp_ops + o.minmax / minmax + o.compare / select;
    const double t_ops = std::max(t_divider, t_ports);

    // 1. the solver, and 4. the fraction.
    std::printf("the solver (real layout, pump, nested 4:1 west of x = -1.2 m, one thread):\n");
    for (auto [res, seconds] : {std::pair{0.02, seconds_2cm}, std::pair{0.01, seconds_1cm}}) {
        const Flow f = run_flow(dem, res, seconds, scratch);
        const double per_update = f.cpu / f.computed;  // [s] per computed cell-update
        const double bandwidth = res > 0.015 ? state_2cm : state_1cm;
        const double t_bytes = work.state_bytes / bandwidth;
        const double limit = std::max(t_ops, t_bytes);
        std::printf("  %g cm over 0-%g s: %.3g cell-updates per processor second (%.3g of them computed, the rest dry land "
                    "skipped), %.1f ns each\n",
                    100 * res, seconds, f.updates / f.cpu, f.computed / f.cpu, 1e9 * per_update);
        std::printf("    limit: %.1f ns per cell-update (operations %.1f ns: divider %.1f, vector ports %.1f; bytes %.1f ns): "
                    "the solver reaches %.0f%% of it, bound by %s\n",
                    1e9 * limit, 1e9 * t_ops, 1e9 * t_divider, 1e9 * t_ports, 1e9 * t_bytes, 100.0 * limit / per_update,
                    t_bytes > t_ops ? "memory" : (t_divider > t_ports ? "the divider" : "the vector ports"));
    }
    return 0;
}
