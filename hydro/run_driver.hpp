// The run driver's parts (run.cpp puts them together): what a run carries besides the
// solver (RunOutput), starting or resuming it, checkpoints, and the stepping loop
// (run_steps.cpp) with its frames, gauges, maxima, checkpoints and stops.
#pragma once
#include <csignal>
#include <optional>
#include <string>
#include <vector>

#include "common/atomic_file.hpp"
#include "common/progress.hpp"
#include "formats/flow_file.hpp"
#include "hydro/boundary_output.hpp"
#include "hydro/run.hpp"
#include "hydro/run_checkpoint.hpp"
#include "hydro/run_frames.hpp"
#include "hydro/run_solver.hpp"

namespace flotsam::hydro {

// What a run carries from start to end besides the solver: the output window and frame
// times, the gauges and the maxima, the file being written and the checkpoint's
// bookkeeping.
struct RunOutput {
    RunOutput(const Scene& scene, const RunDef& run, const PhysicsDef& def);
    Window win;
    std::vector<double> times;
    std::vector<FlowGauge> gauge_points;
    Gauges gauges;
    Summary sum;
    std::string key;  // restart_key() of this run
    AtomicOutput file;
    std::string checkpoint;
    std::optional<FlowWriter> writer;
    std::optional<BoundaryOutput> outline;  // --boundary-output
    Checkpoint state;                       // where the run stands (its time and counters are set when saved)
};

// The scene's bed on the output window [m].
std::vector<float> window_bed(const Scene& scene, const Window& win);

// A fresh run: creates the file and stores the initial state (frame 0, the maxima and
// the gauges at t = 0).
void start_run(RunSolver& solver, const Scene& scene, const RunDef& run, const PhysicsDef& def, RunOutput& o);

// A restart: the state, maxima and partial file of the interrupted run, if they were
// written with the same settings, scene and boundary files and are intact.
void resume_run(RunSolver& solver, RunOutput& o);

// Saves the exact state at time t after `steps` steps, so that --restart continues to
// the same result. From then on the partial output belongs to the checkpoint: kept
// whatever happens to the run.
void save_checkpoint(RunSolver& solver, const PhysicsDef& def, RunOutput& o, double t, long steps);

// Set by request_stop (a signal handler).
extern volatile std::sig_atomic_t stop_signal;

// Steps to the last frame, storing frames, gauges, maxima and checkpoints on the way.
// Returns the step count since the start of the run (restarts included), negated when
// the run stopped early (run.stop_after or a signal).
long step_to_end(RunSolver& solver, const RunDef& run, const PhysicsDef& def, RunOutput& o, Progress& progress);

}  // namespace flotsam::hydro
