// Ritter's dam break onto dry ground: where the finite-volume front stands
// and why. Prints tables, asserts nothing (tests/hydro_front_test.cpp asserts a subset);
// docs/hydro.md, "Wet/dry fronts", shows its output.
//
//   ritter_front [--max-cells N]   (default 1600; about 4 s in all)
//
// The case (cases/hydro_cases.hpp, ritter_box): [0, 10] m, dam at 5 m, h0 of still water
// west of it, 4 rows, walls, no friction, every other setting at its default. The front
// is the east edge of the last cell with h > 5e-7 m; the exact position of that depth is
// x_f = 5 + 2 c0 t - t sqrt(9 g 5e-7), c0 = sqrt(g h0) (h = (2 c0 - xi)^2 / (9 g) in the
// fan). Three tables:
//   1. the defaults: lag of the front behind x_f in cells, the L1 error of h and its order;
//   2. the same at 400 cells with the dry tolerance from 1e-5 down to 1e-12 m: does the
//      tolerance hold water back?
//   3. the same at 400 cells started from the exact solution at t0 (the fan already
//      t0 c0 / dx cells wide): is the lag made at the start or on the way?
//   4. the lag at 100-400 cells of the front defined by deeper water, 1e-5 to 1e-3 m
//      (exact position 5 + 2 c0 t - t sqrt(9 g h)): how far the depths that matter lag.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "cases/hydro_cases.hpp"
#include "hydro/solver.hpp"

using namespace flotsam;
using namespace flotsam::hydro;

namespace {

constexpr double kFrontDepth = 5e-7;  // [m]

test::RitterFront run(int nx, double h0, double t0, double t_end, double dry_depth, double front_depth = kFrontDepth) {
    return test::ritter_front(nx, h0, t0, t_end, front_depth, [dry_depth](const Scene& s, PhysicsDef d) {
        d.dry_depth = dry_depth;
        return Solver(s, d);
    });
}

struct Depth {
    double h0, t_end;  // [m], [s]: both put the exact tip at 7.658 m
};
constexpr Depth kDepths[] = {{0.005, 6.0}, {0.02, 3.0}};

}  // namespace

int main(int argc, char** argv) {
    int max_cells = 1600;
    for (int a = 1; a < argc; ++a) {
        if (std::strcmp(argv[a], "--max-cells") == 0 && a + 1 < argc) {
            max_cells = std::atoi(argv[++a]);
        } else {
            std::fprintf(stderr, "usage: ritter_front [--max-cells N]\n");
            return 2;
        }
    }
    const double dry = PhysicsDef{}.dry_depth;
    std::printf("1. Defaults (dry tolerance %.0e m): front lag behind x_f [cells], L1 error of h [m^2], order\n\n", dry);
    std::printf(
        "| h0, t | cells | front [m] | x_f [m] | lag [m] | lag [cells] | L1 [m^2] | order |\n| --- | --- | --- | --- | --- | --- | "
        "--- | --- |\n");
    for (const Depth& c : kDepths) {
        double previous = 0.0;
        for (int nx = 100; nx <= max_cells; nx *= 2) {
            const test::RitterFront r = run(nx, c.h0, 0.0, c.t_end, dry);
            char order[16] = "";
            if (previous > 0.0) std::snprintf(order, sizeof order, "%.2f", std::log2(previous / r.l1));
            std::printf("| %g mm, %g s | %d | %.4f | %.4f | %.3f | %.1f | %.3e | %s |\n", 1e3 * c.h0, c.t_end, nx, r.front,
                        r.exact_front, r.exact_front - r.front, (r.exact_front - r.front) / r.dx, r.l1, order);
            previous = r.l1;
        }
    }
    std::printf(
        "\n2. 400 cells, the dry tolerance varied: lag [cells] (L1 [m^2])\n\n| h0 | 1e-5 m | 1e-7 m | 1e-9 m | 1e-12 m |\n"
        "| --- | --- | --- | --- | --- |\n");
    for (const Depth& c : kDepths) {
        std::printf("| %g mm |", 1e3 * c.h0);
        for (double eps : {1e-5, 1e-7, 1e-9, 1e-12}) {
            const test::RitterFront r = run(400, c.h0, 0.0, c.t_end, eps);
            std::printf(" %.1f (%.2e) |", (r.exact_front - r.front) / r.dx, r.l1);
        }
        std::printf("\n");
    }
    std::printf(
        "\n3. 400 cells, started from the exact solution at t0: lag [cells] (L1 [m^2])\n\n"
        "| h0 | t0 = 0 | 0.05 s | 0.1 s | 0.2 s | 0.5 s | 1 s (half these at 2 cm) |\n| --- | --- | --- | --- | --- | --- | --- "
        "|\n");
    for (const Depth& c : kDepths) {
        std::printf("| %g mm |", 1e3 * c.h0);
        for (double t0 : {0.0, 0.05, 0.1, 0.2, 0.5, 1.0}) {
            // The same fan width in cells for both depths: t0 scaled by c0(5 mm) / c0.
            const double t = t0 * std::sqrt(0.005 / c.h0);
            const test::RitterFront r = run(400, c.h0, t, c.t_end, dry);
            std::printf(" %.1f (%.2e) |", (r.exact_front - r.front) / r.dx, r.l1);
        }
        std::printf("\n");
    }
    std::printf(
        "\n4. Defaults, the front defined by deeper water: lag behind the exact position of that depth [cells]\n\n"
        "| h0, t | cells | 1e-5 m | 1e-4 m | 1e-3 m |\n| --- | --- | --- | --- | --- |\n");
    for (const Depth& c : kDepths)
        for (int nx = 100; nx <= std::min(400, max_cells); nx *= 2) {
            std::printf("| %g mm, %g s | %d |", 1e3 * c.h0, c.t_end, nx);
            for (double depth : {1e-5, 1e-4, 1e-3}) {
                const test::RitterFront r = run(nx, c.h0, 0.0, c.t_end, dry, depth);
                std::printf(" %.1f |", (r.exact_front - r.front) / r.dx);
            }
            std::printf("\n");
        }
    return 0;
}
