// Sweep benchmark: the paper's full sensitivity sweep, 10 flows × 2 bodies (FD, LD) ×
// 2 variants (CC+SC, LC+MC) × 9 parameter sets (control and Cd1, Cd2, Cm, Fc × 1.5 and
// / 1.5) = 360 body-runs, through `flotsam sweep`'s own code path (spec file, one World
// per flow, sweep file and CSV summary written). Prints wall time, body-runs per second,
// frames read, and the time in I/O (reading frames, writing outputs) against compute,
// and per core: body steps per wall second and thread, reading against stepping in
// processor time.
// Not a test: timings belong here. The floor: under 5 minutes on 2 cores at 2 cm.
//
//   build/sweep_bench [--threads N] [--no-read-ahead] [--netcdf-reads] [--decode-threads N] [--ground FILE] [--dt-max S] [--out DIR] SCENE FLOW [FLOW ...]
//
// --netcdf-reads: read the flows' h, u, v through netCDF instead of decoding their chunks
// (FlowReaderDef::decode_tiles; the same values), to compare the two.
// --decode-threads N: threads that decode a frame's tiles (default: the stepping threads).
// --dt-max S: the debris step's upper bound [s]; default 0.02, as the paper's spec files
// (sweep/examples/paper_sensitivity*.toml; docs/sweep.md "The step").
//
// --ground FILE: the bodies stand on that finer scene's ground (`flotsam sweep --ground`;
// the pipeline's default at 2 and 4 cm).
//
// --threads N: the stepping threads; with read-ahead (the default, as in `flotsam sweep`)
// one more thread reads the next frame meanwhile, and "frame reading" is the time the
// stepping waited for frames.
//
// With fewer than ten flows the given ones are reused in turn (each reuse opens and
// reads the file again, as a different flow would be read); the output says so.
#include <omp.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "common/atomic_file.hpp"
#include "sweep/sweep.hpp"

using namespace flotsam;

int main(int argc, char** argv) {
    int threads = 2;
    bool read_ahead = true;
    bool decode_tiles = true;
    int decode_threads = 0;
    std::string dir = (std::filesystem::temp_directory_path() / "flotsam-sweep-bench").string();
    std::string ground;
    std::string dt_max = "0.02";  // [s], as TOML text: the spec reader checks it
    double window_margin = -1.0;  // [body lengths]; < 0: debris::WorldDef's default
    std::vector<std::string> args;
    for (int k = 1; k < argc; ++k) {
        const std::string a = argv[k];
        if (a == "--threads" && k + 1 < argc)
            threads = std::atoi(argv[++k]);
        else if (a == "--no-read-ahead")
            read_ahead = false;
        else if (a == "--netcdf-reads")
            decode_tiles = false;
        else if (a == "--decode-threads" && k + 1 < argc)
            decode_threads = std::atoi(argv[++k]);
        else if (a == "--out" && k + 1 < argc)
            dir = argv[++k];
        else if (a == "--ground" && k + 1 < argc)
            ground = argv[++k];
        else if (a == "--dt-max" && k + 1 < argc)
            dt_max = argv[++k];
        else if (a == "--window-margin" && k + 1 < argc)
            window_margin = std::atof(argv[++k]);
        else
            args.push_back(a);
    }
    if (args.size() < 2) {
        std::fprintf(stderr,
                     "usage: sweep_bench [--threads N] [--no-read-ahead] [--netcdf-reads] [--decode-threads N] [--ground FILE] [--dt-max S] [--window-margin LENGTHS] [--out DIR] "
                     "SCENE FLOW [FLOW ...]\n");
        return 2;
    }
    const std::string scene = args[0];
    const std::vector<std::string> given(args.begin() + 1, args.end());
    std::vector<std::string> flows;
    for (int k = 0; k < 10; ++k) flows.push_back(given[std::size_t(k) % given.size()]);
    std::filesystem::create_directories(dir);

    std::string spec_text = "[sweep]\nscene = \"" + scene + "\"\noutput-interval = 1.0\ndt-max = " + dt_max + "\n";
    if (!ground.empty()) spec_text += "ground = \"" + ground + "\"\n";
    spec_text += "[flows]\npaths = [\n";
    for (const auto& f : flows) spec_text += "  \"" + f + "\",\n";
    spec_text +=
        "]\n[[body]]\nstart = \"FD\"\n[[body]]\nstart = \"LD\"\n[variants]\nnames = [\"CC+SC\", \"LC+MC\"]\n"
        "[parameters]\ndesign = \"one_at_a_time\"\nfactor = 1.5\nvary = [\"cd1\", \"cd2\", \"cm\", \"mu\"]\n";
    const std::string spec_path = dir + "/paper_sweep.toml";
    write_text_atomic(spec_path, spec_text);

    try {
        const auto t0 = std::chrono::steady_clock::now();
        sweep::SweepSpec spec = sweep::read_sweep_spec(spec_path);
        spec.world.flow.decode_tiles = decode_tiles;
        spec.world.flow.decode_threads = decode_threads;
        if (window_margin >= 0.0) spec.world.window_margin_lengths = window_margin;
        sweep::SweepRunDef def;
        def.threads = threads;
        def.read_ahead = read_ahead;
        def.quiet = true;
        sweep::SweepRunStats st;
        const sweep::SweepResult r = sweep::run_sweep(spec, def, &st);
        const auto t1 = std::chrono::steady_clock::now();
        sweep::write_sweep_file(dir + "/sweep.nc", r);
        sweep::write_summary_csv(dir + "/sweep.csv", r);
        const auto t2 = std::chrono::steady_clock::now();
        const double run = std::chrono::duration<double>(t1 - t0).count(), write = std::chrono::duration<double>(t2 - t1).count();
        const double wall = run + write, io = st.io_seconds + write, compute = wall - io;

        std::printf("sweep bench: %zu distinct flow file(s) given", given.size());
        if (given.size() < 10)
            std::printf(", reused in turn to make the paper's ten (each reuse re-reads the file; the OS may cache it)");
        std::printf("\n  scene %s, first flow %s\n", scene.c_str(), given.front().c_str());
        std::printf("  members: %d = %zu flows x %zu bodies x %zu variants x %zu parameter sets; %zu output times (%.0f s)\n",
                    st.members, spec.flows.size(), spec.bodies.size(), spec.variants.size(), spec.params.size(), r.time.size(),
                    r.time.back());
        std::printf("  debris step: dt-max %g s\n", spec.world.step.dt_max);
        if (decode_tiles)
            std::printf("  flow tiles: decoded by flotsam (formats/tile_decoder) where the layout allows, on %d thread(s)\n",
                        decode_threads > 0 ? decode_threads : threads);
        else
            std::printf("  flow tiles: read through netCDF (--netcdf-reads)\n");
        std::printf("  threads: %d stepping (OpenMP max %d)%s\n", threads, omp_get_max_threads(),
                    read_ahead ? " + 1 reading ahead" : ", no read-ahead");
        std::printf("  wall time: %.1f s (run %.1f s, writing outputs %.1f s)\n", wall, run, write);
        std::printf("  body-runs/s: %.2f (one 420 s body-run: %.3f s of wall time)\n", st.members / wall, wall / st.members);
        std::printf("  body steps: %ld (%.0f steps/s over compute time)\n", st.steps, double(st.steps) / compute);
        std::printf("  frames read: %zu over %zu flow openings (%.1f per flow); %zu refit to a moved window (its new tiles read)\n",
                    st.frames_loaded, st.flows_opened, double(st.frames_loaded) / double(st.flows_opened), st.frames_refit);
        std::printf("  window margin: %g body lengths beyond each body's reach\n", spec.world.window_margin_lengths);
        std::printf("  cells read: %.3g a frame read (refits' included), %.0f %% of the bodies' bounding windows (only the tiles under the bodies)\n",
                    double(st.cells_read) / double(std::max<std::size_t>(st.frames_loaded, 1)),
                    100.0 * double(st.cells_read) / double(std::max<std::size_t>(st.window_cells, 1)));
        std::printf("  I/O: %.1f s (%.0f %%) = frame reading %.1f s + output writing %.1f s; compute %.1f s (%.0f %%)\n", io,
                    100 * io / wall, st.io_seconds, write, compute, 100 * compute / wall);
        std::printf("  reading CPU time: %.1f s (%s)\n", st.read_cpu_seconds,
                    read_ahead ? "mostly on the read-ahead thread, beside the stepping" : "on the stepping thread");
        rusage use{};
        getrusage(RUSAGE_SELF, &use);
        const double cpu =
            double(use.ru_utime.tv_sec + use.ru_stime.tv_sec) + 1e-6 * double(use.ru_utime.tv_usec + use.ru_stime.tv_usec);
        std::printf("  processor time: %.1f s (all threads); %.3g body steps per processor second (goal 5e6 per core)\n", cpu,
                    double(st.steps) / cpu);
        // Reading (NetCDF, the ground's depths) against stepping (all else: the body steps,
        // the waits at the stepping threads' barriers, writing), in processor time.
        const double stepping_cpu = std::max(cpu - st.read_cpu_seconds, 1e-9);
        std::printf("  per core: %.3g body steps per wall second and stepping thread; processor time reading %.1f s (%.0f %%), "
                    "stepping %.1f s (%.3g body steps per stepping processor second)\n",
                    double(st.steps) / (wall * threads), st.read_cpu_seconds, 100 * st.read_cpu_seconds / cpu, stepping_cpu,
                    double(st.steps) / stepping_cpu);
        std::printf(
            "  floor (paper sweep under 300 s on 2 cores at 2 cm): %s; wall goals on 2 cores: 20 s at 1 cm "
            "(floor 60 s), 10 s at 4 cm\n",
            wall < 300 ? "met" : "NOT met");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "sweep_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
