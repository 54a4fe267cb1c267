// The sweep file: every member's trajectory in one CF-1.11 trajectory file (orthogonal
// multidimensional representation, all members on one time axis), with what each member
// is (flow, body, start perturbation, model variant, parameter set) as per-trajectory
// variables, and the sweep's tables (flows, parameter sets) on their own dimensions.
// Variable names are listed in docs/sweep.md.
//
// A shard holds a contiguous block of member ids; merge_sweeps() joins blocks into the
// whole sweep, and writes the same bytes as an unsharded run (nothing in the file
// depends on how the sweep was split, on the command line or on the clock).
#pragma once
#include <array>
#include <string>
#include <vector>

#include "common/cf.hpp"
#include "common/grid.hpp"
#include "common/netcdf.hpp"
#include "debris/world.hpp"
#include "formats/impact_file.hpp"
#include "formats/trajectory_file.hpp"
#include "sweep/members.hpp"
#include "sweep/spec_file.hpp"

namespace flotsam::sweep {

struct MemberRecord : MemberIndex {
    std::string body_name, start_name, variant_name;
    debris::BodyDef def;      // the body as run: start x, y [m], shape, coefficients, model, variant
    double heading0_deg = 0;  // start heading [degree] (def.heading, as written in the file)
    debris::BodyStats counts;  // its steps' counts (debris/body.hpp; `steps` itself is not recorded)
    debris::Track track;  // on SweepResult::time
    std::vector<Impact> impacts;  // on buildings, by time (Impact::trajectory: unused here, the file's index when written)
};

struct SweepResult {
    // The sweep as a whole (identical in every shard).
    std::string spec_file, spec_sha256, scene_file, design;
    std::string ground_file;  // the bodies' finer ground (debris::Ground; "": the flows' beds)
    std::vector<std::string> flows, bodies, variants;
    std::vector<std::string> body_types, body_sources;  // per body: catalogue entry, GIS feature "layer/fid" ("" : none)
    std::vector<ParameterSet> params;
    PerturbationDef perturbation;
    int member_count = 0;          // members in the whole sweep
    double output_interval = 0.0;  // [s]
    debris::WorldDef world;        // step and flow replay settings (threads: not recorded)
    std::vector<double> time;      // output times [s]
    cf::GridMapping crs;           // the flows' CRS; empty: local metres
    std::string scene_buildings_sha256;  // the flows' scene (formats/scene.hpp); empty: not recorded
    std::string path;               // the file it was read from, for messages ("": not read from a file)
    // This part.
    Shard shard;                        // {0, 1}: the whole sweep
    std::vector<MemberRecord> members;  // by increasing id
};

// The parameter-set table (param_set_label, param_set_is_control, param_set_<name>) on
// dimension `dim`: written alike in sweep files and statistics files.
struct ParameterSetVariables {
    int label, is_control;
    std::vector<int> value;  // in the order of design_parameters()
};
ParameterSetVariables define_parameter_set_variables(nc::File& f, int dim, const std::vector<ParameterSet>& sets);
void put_parameter_sets(nc::File& f, const ParameterSetVariables& vars, const std::vector<ParameterSet>& sets);

// Writes atomically.
void write_sweep_file(const std::string& path, const SweepResult& r);
// Reads a sweep file (a shard or the whole); errors name the file and variable. The
// tracks are checked as formats/trajectory_file.hpp's TrackReader checks them.
SweepResult read_sweep_file(const std::string& path);
// The same, without the tracks (the members' are empty): the member table checked
// against the sweep's tables (member ids, flow, body, variant and parameter-set indices,
// the body settings), for readers that take the tracks through TrackReader themselves.
SweepResult read_sweep_tables(const std::string& path);

// Throws naming the file and the member when a track leaves grid `g` (`what`: "the grid
// of the scene s.nc"): a body never leaves the grid it moved on, so a sweep whose tracks
// do is not of that scene, or its positions are wrong.
void check_tracks_on(const SweepResult& r, const Grid& g, const std::string& what);

// Joins shards of one sweep (same spec hash and member count; every member exactly
// once). Errors name the offending part.
SweepResult merge_sweeps(const std::vector<SweepResult>& parts, const std::vector<std::string>& paths);

// A member's trajectory_id: body/variant/parameter set/flow/perturbation.
std::string trajectory_label(const SweepResult& r, const MemberRecord& m);
// Every member's impacts, in member order, each naming its member's index in the file.
std::vector<Impact> file_impacts(const SweepResult& r);

// One row per trajectory (columns in docs/sweep.md); written atomically (sweep_csv.cpp).
void write_summary_csv(const std::string& path, const SweepResult& r);
// One row per impact on a building (formats/impact_file.hpp; the trajectory's index in the
// file and its label); written atomically.
void write_impacts_summary_csv(const std::string& path, const SweepResult& r);

// out.nc → out.csv
std::string summary_path_for(const std::string& nc_path);
// out.nc → out_impacts.csv
std::string impacts_path_for(const std::string& nc_path);

}  // namespace flotsam::sweep
