// Running a sweep: one World per flow with every member on that flow in it, so each
// pair of frames is read once and all members advance through it together (in
// parallel over members with OpenMP).
#pragma once
#include <cstddef>
#include <string>

#include "sweep/sweep_file.hpp"
#include "sweep/sweep_spec.hpp"

namespace flotsam::sweep {

struct SweepRunDef {
    Shard shard;             // which block of members to run
    int threads = 0;         // OpenMP threads over members; 0: the OpenMP default
    bool read_ahead = true;  // one more thread reads the next frame meanwhile (debris::WorldDef::read_ahead)
    bool quiet = false;      // no progress lines
    bool allow_large_run = false;  // run even past the bounds of debris::check_replay_work
};

// What the run cost, for reports and the benchmark.
struct SweepRunStats {
    std::size_t flows_opened = 0;
    std::size_t frames_loaded = 0;  // frame reads, over all flows
    std::size_t frames_refit = 0;   // frames brought to a moved window (only its new tiles read)
    std::size_t cells_read = 0;     // cells read, of those frames and refits (the tiles under the bodies)
    std::size_t window_cells = 0;   // cells of their windows (the bodies' bounding box)
    double io_seconds = 0.0;        // wall time the stepping waited for frames (read, or being read ahead) [s]
    double read_cpu_seconds = 0.0;  // CPU time of the reading, on whichever thread [s]
    double wall_seconds = 0.0;      // the whole run, without writing the outputs [s]
    long steps = 0;                 // body steps, all members
    int members = 0;                // members run
};

// The output time axis of a sweep: t0 + k Δ up to the end time (the spec's, or the
// earliest last frame). Every flow must start at the same time (else an error naming it).
std::vector<double> sweep_output_times(const SweepSpec& spec);

SweepResult run_sweep(const SweepSpec& spec, const SweepRunDef& def, SweepRunStats* stats = nullptr);

}  // namespace flotsam::sweep
