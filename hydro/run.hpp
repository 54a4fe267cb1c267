// One hydrodynamic run: a scene, a solver configuration, and what to store. Writes the
// flow file (flow_file.hpp) under a temporary name and renames it when complete;
// checkpoints let an interrupted run continue to the same result.
#pragma once
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "formats/flow_file.hpp"
#include "hydro/boundary_output.hpp"
#include "hydro/leapfrog.hpp"
#include "hydro/nesting.hpp"
#include "hydro/run_solver.hpp"
#include "hydro/solver.hpp"

namespace flotsam::hydro {

// The numerical scheme of a run: finite volumes (solver.hpp, the default) or the
// staggered leap-frog of the classic tsunami codes (leapfrog.hpp).
enum class Scheme { finite_volume, leapfrog };
inline constexpr EnumNames<Scheme, 2> scheme_names{"scheme", {{{Scheme::finite_volume, "fv"}, {Scheme::leapfrog, "leapfrog"}}}};
constexpr const auto& enum_names(Scheme) { return scheme_names; }

struct RunDef {
    std::string scene_file;
    std::string out_file;
    double duration = 420.0;                      // [s] simulated time
    double output_interval = 1.0;                 // [s] between stored frames
    std::optional<std::array<double, 4>> window;  // x_min, x_max, y_min, y_max [m] of stored frames
    double gauge_interval = 0.05;                 // [s] between gauge samples
    std::vector<FlowGauge> gauges;                // added to the scene's gauge points
    BoundaryOutputDef boundary_output;            // level and velocity on a box's outline (boundary_output.hpp)
    Scheme scheme = Scheme::finite_volume;
    FiniteVolumeDef finite_volume;                  // --scheme fv only
    LeapfrogDef leapfrog = default_leapfrog_def();  // --scheme leapfrog only; its step divides output_interval
    NestDef nest = default_nest_def();              // nested(): coarse grids in the flume, or where no debris goes (hydro/nesting.hpp); fv only
    double arrival_depth = 0.025;                   // [m] threshold of the arrival-time map (the draft)
    double flood_depth = 0.001;                     // [m] threshold of the flooded flag and the runup
    double checkpoint_interval = 0.0;               // [s] simulated time between checkpoints; 0: none
    bool restart = false;                           // continue from <out>.checkpoint.nc
    double stop_after = -1.0;                       // [s] stop (as if interrupted) once past this time; < 0: never
    int realisation = -1;                           // boundary realisation id, recorded in the file
    int deflate_level = 1;                          // 0..9
    std::string command_line;                       // for `history`
    std::string config_text;                        // effective configuration (TOML), for `flotsam_config`
    std::string label = "hydro";                    // progress label
    bool quiet = false;
    bool allow_large_run = false;  // run even when the estimated work passes max_cell_updates (common/checks.hpp)
};

struct RunResult {
    bool completed = false;  // false when stopped by stop_after or request_stop
    int stop_signal = 0;     // the signal request_stop was given, where it stopped the run
    double checkpoint_time = -1.0;  // [s] of the checkpoint an interrupted run left; < 0: none
    long steps = 0;                               // taken by this run (since its checkpoint, with --restart)
    double started = 0.0;                         // simulated time it began at: 0, or its checkpoint's [s]
    double simulated = 0.0;                       // simulated time it ended at [s]
    double wall_seconds = 0.0;                    // stepping only, excluding setup (with the per-step
                                                  // maxima, gauges, frames and checkpoints)
    double cpu_seconds = 0.0;                     // processor time of the same, all threads [s]
    double cell_updates_per_second = 0.0;         // interior cells x steps / wall_seconds
    double dry_skipped_fraction = 0.0;            // of the cell updates, skipped as dry land (solver.hpp)
    double volume_start = 0.0, volume_end = 0.0;  // [m^3]
    long negative_depth_fixes = 0;
    long positivity_redos = 0;  // steps redone at cfl 0.45 (cfl > 0.5 only)
    long outflow_limits = 0;    // leap-frog: cell-steps whose outflow was scaled down
    std::size_t file_bytes = 0;
};

// The bytes a run may write (its frames, gauges and boundary outline, uncompressed)
// without --allow-large-run: more than any study here writes (a 1 cm flow with frames
// every second over 420 s: 2e9), far below a run that fills a disk.
inline constexpr double max_output_bytes = 1e10;

// A run of `run.scheme` on the physics and boundaries of `physics`.
RunResult run_hydro(const RunDef& run, const PhysicsDef& physics);

// Asks a run under way to stop at its next stored frame and write a checkpoint there, as
// stop_after does, so that --restart continues it to the bytes of an uninterrupted run;
// when that frame is more than about a second of wall time away, the run stops at once,
// keeping the checkpoint it last wrote (if any) and its partial output.
// Async-signal-safe: the hydro command calls it from its SIGTERM, SIGINT and SIGHUP
// handler (a batch system's notice before it kills a job). `signal` is reported back in
// RunResult::stop_signal.
void request_stop(int signal);

// Path of the checkpoint that belongs to an output file.
std::string checkpoint_path(const std::string& out_file);

}  // namespace flotsam::hydro
