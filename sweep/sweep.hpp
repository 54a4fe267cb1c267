// Running a sweep: its inputs opened and checked once (open_sweep), then one World per
// flow with every member on that flow in it, so each pair of frames is read once and all
// members advance through it together (in parallel over members with OpenMP).
// `flotsam debris` is a sweep of one flow and one member per body.
#pragma once
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "debris/flow_reader.hpp"
#include "formats/scene.hpp"
#include "sweep/members.hpp"
#include "sweep/spec_file.hpp"
#include "sweep/sweep_file.hpp"

namespace flotsam::sweep {

// How messages name the settings a run is checked on: a spec's keys (the default) or a
// command's options, and the file they come from ("" : the command line).
struct SettingNames {
    std::string dt_max = "[sweep] dt-max";
    std::string vertex_step_fraction = "[sweep] vertex-step-fraction";
    std::string output_interval = "output_interval";
    std::string end_time = "end_time";
};

struct SweepRunDef {
    Shard shard;             // which block of members to run
    int threads = 0;         // OpenMP threads over members; 0: the OpenMP default
    bool read_ahead = true;  // one more thread reads the next frame meanwhile (debris::WorldDef::read_ahead)
    bool quiet = false;      // no progress lines
    bool allow_large_run = false;  // run even past the bounds of debris::check_replay_work
    std::string progress_label;    // progress lines' label ("" : "sweep flow k/n (m members)")
    SettingNames names;            // how errors name the settings
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

// A sweep's inputs, each file opened and checked once before any body steps, then handed
// down as values.
struct SweepInputs {
    SweepSpec spec;
    std::shared_ptr<const Scene> scene;                      // the spec's scene (null: none)
    std::shared_ptr<const Scene> ground;                     // the bodies' finer ground (null: the flows' beds)
    std::vector<std::unique_ptr<debris::FlowReader>> flows;  // spec.flows, open (each moves into its world when run)
    std::vector<Member> members;                             // every member of the sweep (enumerate_members)
    std::vector<double> times;                               // output times [s]
    debris::WorldDef world;                                  // spec.world, the settings that follow the bodies set
};

// Opens the ground and the flows, enumerates the members and the output times, and
// checks the work of `def`'s shard against the bounds (common/checks.hpp) unless
// allowed. `scene` is the spec's scene as read_sweep_spec read it (null: read here when
// the spec names one). Every flow must start at the same time (else an error naming it).
SweepInputs open_sweep(SweepSpec spec, std::shared_ptr<const Scene> scene, const SweepRunDef& def);

// Runs `def`'s shard of the sweep; the flows' readers are used up.
SweepResult run_sweep(SweepInputs& inputs, const SweepRunDef& def, SweepRunStats* stats = nullptr);
// open_sweep, then run_sweep.
SweepResult run_sweep(const SweepSpec& spec, const SweepRunDef& def, SweepRunStats* stats = nullptr);

// The counts the end of a run reports (docs/debris.md, "Collisions"): jammed and
// unresolved collision steps over the members, and how many members had any.
struct CollisionReport {
    long jammed = 0, unresolved = 0, members = 0;
};
CollisionReport collision_report(const SweepResult& r);

}  // namespace flotsam::sweep
