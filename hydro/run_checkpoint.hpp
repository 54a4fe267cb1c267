// Checkpoints of a hydro run (run_driver.hpp): the solver's exact state, the maxima so far and
// where the output stands, so that --restart continues an interrupted run to the bytes
// of an uninterrupted one. Written atomically; the restart key (restart_key.hpp) says
// which settings, scene and boundary files wrote it, and a SHA-256 of everything it holds
// (`state_sha256`) that a damaged file cannot match.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "common/netcdf.hpp"
#include "hydro/physics.hpp"
#include "hydro/run_frames.hpp"

namespace flotsam::hydro {

struct Checkpoint {
    double time = 0.0;
    long steps = 0;
    std::size_t next_frame = 0, next_gauge = 0;
    double volume_start = 0.0;
    double pump_level = 0.0;
    bool pump_stopped = false;
    std::string key;  // restart_key() of the run that wrote it
};

// Writes the state arrays (each in its own type), the maxima and the bookkeeping to
// `path` (through <path>.part). A full disk is named as such.
void write_checkpoint(const std::string& path, const std::vector<StateArray>& state, const Summary& sum, const Checkpoint& c);

// Reads a checkpoint into `state` (sized as the solver's) and `sum`; throws naming the
// file when it is not a flotsam checkpoint, its arrays do not fit this solver, or what it
// holds does not match its checksum (a damaged file).
Checkpoint read_checkpoint(const std::string& path, const std::vector<StateArray>& state, Summary& sum);

// The simulated time a checkpoint was written at [s]; < 0 when it has none.
double read_checkpoint_time(const std::string& path);

// The restart key a checkpoint holds; throws for one written before they held keys.
std::string read_checkpoint_key(const std::string& path);

// The SHA-256 of a checkpoint's contents: its bookkeeping, state arrays and maxima.
std::string checkpoint_checksum(const Checkpoint& c, const std::vector<StateArray>& state, const Summary& sum);

}  // namespace flotsam::hydro
