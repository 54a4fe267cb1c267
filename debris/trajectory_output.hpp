// Recording a world's bodies over time and writing them as a trajectory file (the schema
// is formats/trajectory_file.hpp).
#pragma once
#include <string>
#include <vector>

#include "debris/world.hpp"
#include "formats/trajectory_file.hpp"

namespace flotsam::debris {

struct TrajectorySeries {
    std::vector<double> time;   // [s]
    std::vector<Track> tracks;  // one per body
};

// Appends the bodies' current states at world.time() and clears their event bits.
void record(World& world, TrajectorySeries& series);

struct TrajectoryFileDef {
    std::string history;                   // the command line
    std::string flow_file;                 // the replayed flow
    std::vector<std::string> start_names;  // per body: the scene point, or "" for --at
    cf::GridMapping crs;                   // the flow's CRS; empty: local metres
};

// Writes atomically (temporary file, then rename).
void write_trajectory_file(const std::string& path, const World& world, const TrajectorySeries& series,
                           const TrajectoryFileDef& def);

}  // namespace flotsam::debris
