// Hydro benchmark: cell-updates per second of the second-order scheme and of the
// leap-frog on the real layout at 2 cm (or the generated scene when the real DEM is not
// at hand), on 1 and 2 threads, and the bytes one stored frame takes. Prints figures;
// asserts nothing.
//
//   hydro_bench [--dem PATH] [--resolution 0.02] [--seconds 4] [--repeat 2] [--scratch DIR]
//
// What is timed is what a run costs: run_hydro's stepping loop, with the per-step
// maxima and arrival times, the gauges and the stored frames (not the setup: reading the
// scene, building the grid). A cell update is one interior cell advanced by one step.
// Each figure is the best of --repeat runs, by wall time and by processor time
// separately: on a shared machine the wall time of a run depends on the other
// processes, its processor time much less (for one thread). The load average is printed
// so that a reader can judge. Lines:
//   - the benchmark: pump forcing from still water, the first seconds; the city is still
//     dry, and exactly-dry cells are skipped (the fraction is printed);
//   - all wet: the same with the water level above every roof, nothing to skip: the
//     cost of a cell in a flooded city;
//   - nested: the flows' default grids (a 4x coarser grid west of x = -1.2 m).
#include <omp.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "cases/bench_scene.hpp"
#include "hydro/run.hpp"

using namespace flotsam;

namespace {

struct Best {
    double wall_rate = 0.0, cpu_rate = 0.0;  // cell-updates per wall / per processor second
    double wall = 0.0, cpu = 0.0;            // [s] of the fastest run
    double simulated = 0.0;                  // [s]
    long steps = 0;
    double dry_skipped = 0.0;
};

Best best_of(int repeat, int threads, hydro::RunDef rd, const hydro::PhysicsDef& sd) {
    omp_set_num_threads(threads);
    Best b;
    for (int k = 0; k < repeat; ++k) {
        const hydro::RunResult r = hydro::run_hydro(rd, sd);
        const double updates = r.cell_updates_per_second * r.wall_seconds;
        if (b.wall == 0.0 || r.wall_seconds < b.wall) b.wall = r.wall_seconds;
        if (b.cpu == 0.0 || r.cpu_seconds < b.cpu) b.cpu = r.cpu_seconds;
        b.wall_rate = std::max(b.wall_rate, updates / r.wall_seconds);
        b.cpu_rate = std::max(b.cpu_rate, updates / r.cpu_seconds);
        b.simulated = r.simulated;
        b.steps = r.steps;
        b.dry_skipped = r.dry_skipped_fraction;
    }
    return b;
}

void print(const char* what, int threads, const Best& b) {
    std::printf(
        "  %-9s %d thread%s: %.3g cell-updates/s (%.3g per processor second); %ld steps, %.2f s wall, %.2f s processor; "
        "%.0f%% dry land skipped\n",
        what, threads, threads > 1 ? "s" : " ", b.wall_rate, b.cpu_rate, b.steps, b.wall, b.cpu, 100.0 * b.dry_skipped);
}

std::string load_average() {
    std::ifstream f("/proc/loadavg");
    std::string one, five;
    f >> one >> five;
    return one.empty() ? "unknown" : one + " (1 min), " + five + " (5 min)";
}

}  // namespace

int main(int argc, char** argv) {
    std::string dem = std::string(FLOTSAM_SHARED_DEFAULT) + "/data/city-topography-from-figure.nc";
    double resolution = 0.02, seconds = 4.0;
    int repeat = 2;
    std::string scratch = (std::filesystem::temp_directory_path() / "flotsam-hydro-bench").string();
    for (int k = 1; k + 1 < argc; k += 2) {
        const std::string a = argv[k];
        if (a == "--dem")
            dem = argv[k + 1];
        else if (a == "--resolution")
            resolution = std::atof(argv[k + 1]);
        else if (a == "--seconds")
            seconds = std::atof(argv[k + 1]);
        else if (a == "--repeat")
            repeat = std::max(1, std::atoi(argv[k + 1]));
        else if (a == "--scratch")
            scratch = argv[k + 1];
    }
    std::filesystem::create_directories(scratch);
    auto [scene, what] = test::bench_scene(dem, resolution);
    const std::string scene_path = scratch + "/scene.nc", wet_path = scratch + "/scene-all-wet.nc";
    write_scene(scene_path, scene, "hydro_bench");
    // All wet: still water 1 cm above the highest ground.
    const double top = *std::max_element(scene.z.begin(), scene.z.end());
    scene.eta0.assign(scene.z.size(), top + 0.01);
    write_scene(wet_path, scene, "hydro_bench");

    // The benchmark forcing: a pump source on the west wall (no boundary file needed).
    hydro::PhysicsDef sd = hydro::default_physics_def();
    sd.west.kind = hydro::BoundaryKind::pump;
    hydro::RunDef rd;
    rd.scene_file = scene_path;
    rd.duration = seconds;
    rd.output_interval = seconds / 2.0;
    rd.quiet = true;
    const char* wait = std::getenv("OMP_WAIT_POLICY");
    std::printf("hydro_bench: %s at %.3g m (%d x %d cells), %.3g s simulated, second order, best of %d\n", what.c_str(), resolution,
                scene.grid.nx, scene.grid.ny, seconds, repeat);
    std::printf("  load average before: %s; OMP_WAIT_POLICY=%s\n", load_average().c_str(), wait ? wait : "(unset)");
    // One case on 1 and then 2 threads; its files are scratch/STEM-1.nc and STEM-2.nc.
    auto on_one_and_two_threads = [&](const char* label, hydro::RunDef run, const std::string& stem) {
        std::array<Best, 2> best;
        for (int threads = 1; threads <= 2; ++threads) {
            run.out_file = scratch + "/" + stem + "-" + std::to_string(threads) + ".nc";
            best[std::size_t(threads - 1)] = best_of(repeat, threads, run, sd);
            print(label, threads, best[std::size_t(threads - 1)]);
        }
        return best;
    };
    const auto [one, two] = on_one_and_two_threads("benchmark", rd, "flow");
    std::printf("  speed-up on 2 threads: %.2fx (wall)\n", two.wall_rate / one.wall_rate);

    hydro::RunDef wet = rd;
    wet.scene_file = wet_path;
    wet.duration = wet.output_interval = std::min(1.0, seconds);
    wet.out_file = scratch + "/flow-wet.nc";
    print("all wet", 1, best_of(repeat, 1, wet, sd));

    hydro::RunDef nested = rd;
    nested.nest = hydro::NestDef{-1.2, 4};
    nested.out_file = scratch + "/flow-nested.nc";
    const Best n = best_of(repeat, 1, nested, sd);
    print("nested", 1, n);
    std::printf("  nested: %.3g simulated s per processor s (a 420 s run: %.0f processor s)\n", n.simulated / n.cpu,
                420.0 * n.cpu / n.simulated);

    // The leap-frog (--scheme leapfrog) on the same run: its fixed step is longer and
    // does one pass of fluxes instead of Heun's two.
    hydro::RunDef leapfrog = rd;
    leapfrog.scheme = hydro::Scheme::leapfrog;
    const auto [lf1, lf2] = on_one_and_two_threads("leap-frog", leapfrog, "flow-leapfrog");
    std::printf("  leap-frog: %.2fx on 2 threads; %.3g simulated s per processor s against %.3g for finite volumes\n",
                lf2.wall_rate / lf1.wall_rate, lf1.simulated / lf1.cpu, one.simulated / one.cpu);

    // Bytes per frame: the same run storing 5 frames instead of 3.
    omp_set_num_threads(2);
    rd.out_file = scratch + "/flow-frames.nc";
    rd.output_interval = seconds / 4.0;
    const auto more = hydro::run_hydro(rd, sd);
    const auto base = std::filesystem::file_size(scratch + "/flow-1.nc");
    std::printf("  bytes per stored frame (h, u, v float32, deflate 1 + shuffle): %.0f\n", double(more.file_bytes - base) / 2.0);
    std::printf("  load average after: %s\n", load_average().c_str());
    std::printf("  (floor: 1e7 cell-updates/s per core, 1.6x on 2 threads)\n");
    return 0;
}
