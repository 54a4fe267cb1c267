// Recording a world's bodies over time and writing them as a trajectory file (the schema
// is formats/trajectory_file.hpp).
#pragma once
#include <string>
#include <vector>

#include "common/netcdf.hpp"
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
    std::vector<std::string> sources;      // per body: the GIS feature "layer/fid" it came from, or ""
    std::vector<std::string> body_types;   // per body: its debris catalogue entry, or ""
    cf::GridMapping crs;                   // the flow's CRS; empty: local metres
    std::string scene_buildings_sha256;         // the flow's scene (formats/scene.hpp); empty: not recorded
};

// A trajectory's step counts (BodyStats; `steps` is not recorded) as variables on the
// trajectory dimension `dim`: collision_steps, unresolved_collisions, axis_shift_steps,
// jammed_steps, largest_residual_overlap [m], body_contact_steps, largest_body_overlap [m];
// written alike in trajectory and sweep files.
struct StepCountVariables {
    int collisions, unresolved, axis_shifts, jams, residual, body_contacts, body_overlap;
};
StepCountVariables define_step_count_variables(nc::File& f, int dim);
void put_step_counts(nc::File& f, const StepCountVariables& v, const std::vector<BodyStats>& counts);

// The step and flow replay settings as global attributes (dt_max_s, vertex_step_fraction,
// max_collision_passes, integrator, time_interpolation), written alike in trajectory and
// sweep files; reading gives the defaults for attributes a file lacks.
void put_world_attributes(nc::File& f, const WorldDef& def);
WorldDef get_world_attributes(const nc::File& f);

// One body over a run, as its trajectory file holds it.
struct TrajectoryRecord {
    BodyDef def;      // the body as run (its start in the flow's coordinates)
    BodyStats stats;  // its step counts
    Track track;      // on the file's time axis
};

// Writes atomically (temporary file, then rename): the records on the time axis `time`,
// the impacts on buildings (by record, then time; Impact::trajectory the record's index),
// and the step and flow replay settings `world` they were run with.
void write_trajectory_file(const std::string& path, const std::vector<TrajectoryRecord>& records, const std::vector<double>& time,
                           const std::vector<Impact>& impacts, const WorldDef& world, const TrajectoryFileDef& def);

}  // namespace flotsam::debris
